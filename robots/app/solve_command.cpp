#include "solve_command.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/gnuplot_figure.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics_option_names.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr_app {

std::shared_ptr<const pcr::RobotModel> load_model(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw UsageError("model file '" + path + "' not found (MODEL must be a URDF file)");
  return std::make_shared<const pcr::RobotModel>(pcr::load_robot_model(path));
}

std::shared_ptr<const pcr::RobotModel> load_model_with_links(const SolveArguments& args) {
  std::shared_ptr<const pcr::RobotModel> model = load_model(args.model_path);
  for (const std::string& link : args.links) model->link_index(link);  // InputError naming an unknown link
  return model;
}

pcr::VecX resolve_inputs(const pcr::RobotModel& model, const std::vector<NamedArgument>& overrides) {
  pcr::VecX inputs = model.default_input_values();
  for (const NamedArgument& arg : overrides) {
    int index = -1;
    for (size_t i = 0; i < model.inputs().size(); ++i)
      if (model.inputs()[i].name == arg.name) index = static_cast<int>(i);
    if (index < 0) {
      std::string valid;
      for (const pcr::ActuationInput& input : model.inputs())
        valid += (valid.empty() ? "" : ", ") + input.name;
      throw UsageError(arg.text() + ": model '" + model.name() + "' has no input '" + arg.name +
                       "' (inputs: " + (valid.empty() ? "none" : valid) + ")");
    }
    const double value = parse_number(arg.value, arg.text());
    const pcr::ActuationInput& input = model.inputs()[index];
    if (value < input.lower || value > input.upper) {
      std::ostringstream message;
      message << arg.text() << ": value " << value << " is outside the bounds [" << input.lower << ", "
              << input.upper << "] of input '" << input.name << "'";
      throw UsageError(message.str());
    }
    inputs[index] = value;
  }
  return inputs;
}

pcr::KinematicsOptions kinematics_options(const SolveArguments& args) {
  pcr::KinematicsOptions options;
  // The word options (already checked by the argument parser; "" where not given).
  const std::pair<const char*, const std::string*> word_options[] = {
      {"solver", &args.solver},
      {"formulation", &args.formulation},
      {"mixed_points", &args.mixed_points},
      {"objective", &args.objective},
      {"contact_method", &args.contact_method}};
  for (const auto& [name, word] : word_options)
    if (!word->empty()) pcr::set_kinematics_option(options, name, *word);
  pcr::RodDiscretization& d = options.assembly.discretization;
  if (args.degree > 0) d.degree = args.degree;
  if (args.elements > 0) d.elements = args.elements;
  if (args.max_stress > 0.0) options.ik.max_rod_stress = args.max_stress;
  if (args.tolerance > 0.0) options.tolerance = args.tolerance;
  if (args.centerline_points > 0) options.centerline_points = args.centerline_points;
  options.stability_verdict = args.stability;
  return options;
}

bool wants_json(const SolveArguments& args) {
  return args.json || !args.json_file.empty();
}

pcr::SolutionExtras solution_extras(const pcr::ForwardKinematics& fk, const pcr::RobotSolution& solution,
                                    const std::vector<std::string>& links, bool derivatives,
                                    std::ostream& err, const std::string& prefix) {
  const pcr::RobotModel& model = fk.assembly().model();
  pcr::SolutionExtras extras;
  extras.links = pcr::link_poses(model, solution, links);
  if (!derivatives || !solution.summary.converged() || !fk.has_solution()) return extras;
  try {
    extras.input_jacobian = fk.input_jacobian();
    for (size_t p = 0; p < model.platforms().size(); ++p)
      extras.compliance.push_back(fk.compliance(static_cast<int>(p)));
  } catch (const pcr::InputError& e) {  // a singular Jacobian: no derivative there
    extras.input_jacobian.resize(0, 0);
    extras.compliance.clear();
    err << prefix << "no input_jacobian and compliance in the JSON: " << e.what() << "\n";
  }
  return extras;
}

void make_parent_directories(const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code ignored;  // a directory that cannot be made shows up when the file is written
  if (!file.empty() && !parent.empty()) std::filesystem::create_directories(parent, ignored);
}

std::ofstream open_output(const std::string& option, const std::string& file) {
  make_parent_directories(file);
  std::ofstream stream(file);
  if (!stream) throw pcr::InputError(option + ": cannot write '" + file + "'");
  return stream;
}

void close_output(std::ofstream& stream, const std::string& option, const std::string& file) {
  stream.close();
  if (stream.fail()) throw pcr::InputError(option + ": error while writing '" + file + "'");
}

int write_outputs(const SolveArguments& args, const pcr::RobotModel& model,
                  const pcr::RobotSolution& solution, const std::vector<pcr::LinkTarget>& targets,
                  const pcr::SolutionExtras& extras, const std::string& title, std::ostream& out,
                  std::ostream& err) {
  const std::string prefix = "pcr " + args.command + ": ";
  int code = kConverged;
  for (const std::string* file : {&args.vtk_path, &args.png_path}) make_parent_directories(*file);
  try {
    if (args.json) {
      const int non_finite = pcr::write_solution_json(out, model, solution, targets, extras);
      if (non_finite > 0) err << prefix << non_finite << " non-finite values written as null\n";
    } else {
      pcr::write_solution_table(out, model, solution);
      pcr::write_link_table(out, extras.links);
    }
    if (!args.json_file.empty()) {
      std::ofstream file = open_output("--json-file", args.json_file);
      pcr::write_solution_json(file, model, solution, targets, extras);
      close_output(file, "--json-file", args.json_file);
    }
    if (!args.csv.empty()) pcr::write_solution_csv(args.csv, model, solution);
    if (!args.vtk_path.empty()) pcr::write_solution_vtk(args.vtk_path, model, solution);
  } catch (const pcr::InputError& e) {
    err << prefix << e.what() << "\n";
    code = kOutputFailed;
  }
  if (!args.png_path.empty()) {
    const pcr::FigureOutcome figure = pcr::write_solution_png(args.png_path, model, solution, title);
    if (!figure.ok) {
      err << prefix << "--png " << args.png_path << ": " << figure.message << "\n";
      code = kOutputFailed;
    }
  }
  return code;
}

}  // namespace pcr_app

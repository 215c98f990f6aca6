// The coarse-mesh continuation and its transfer to the requested mesh (coarse_continuation.hpp).
#include "coarse_continuation.hpp"

#include <unordered_map>
#include <utility>

#include "continuation_weights.hpp"
#include "pcr/core/error.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::kinematics {

MeshTransfer::MeshTransfer(const RobotAssembly& from, const RobotAssembly& to) {
  const Problem &pf = from.problem(), &pt = to.problem();
  if (from.num_rods() != to.num_rods()) return;
  to_size_ = pt.num_variables();
  std::vector<bool> covered(static_cast<size_t>(to_size_), false);
  for (int i = 0; i < from.num_rods(); ++i) {
    const CollocationRod &a = from.rod(i), &b = to.rod(i);
    // A rod with contact only on the same knots (its contact rows hold at the knot spans' midpoints): its
    // contact multipliers are then copied by name below.
    const bool same_knots =
        a.knots().degree() == b.knots().degree() && a.knots().knots() == b.knots().knots();
    if (a.control_point_size() != b.control_point_size() ||
        ((from.rod_contact(i) || to.rod_contact(i)) && !same_knots) ||
        a.discretization().formulation != b.discretization().formulation)
      return;
    // Control points of b interpolating a's curve at b's Greville abscissae tau: B_b(tau) P_b = B_a(tau) P_a.
    const std::vector<double> tau = b.knots().greville();
    SparseLu lu;
    if (!lu.compute(collocation_matrix(b.knots(), tau, 0))) return;
    RodMap m{from.rod_variables(i).control_point_offset,
             to.rod_variables(i).control_point_offset,
             a.num_control_points(),
             b.num_control_points(),
             b.control_point_size(),
             lu.solve(MatX(collocation_matrix(a.knots(), tau, 0)))};
    std::fill(covered.begin() + m.to_offset, covered.begin() + m.to_offset + m.to_points * m.point_size,
              true);
    rods_.push_back(std::move(m));
  }
  std::unordered_map<std::string, int> from_blocks;
  for (int k = 0; k < pf.num_variable_blocks(); ++k) from_blocks[pf.variable(k).name] = k;
  for (int k = 0; k < pt.num_variable_blocks(); ++k) {
    const VariableBlock& b = pt.variable(k);
    if (b.size == 0 || covered[static_cast<size_t>(b.offset)]) continue;
    const auto it = from_blocks.find(b.name);
    if (it == from_blocks.end() || pf.variable(it->second).size != b.size) return;
    copies_.push_back({pf.variable(it->second).offset, b.offset, b.size});
  }
  valid_ = true;
}

VecX MeshTransfer::apply(const VecX& from_x) const {
  VecX out = VecX::Zero(to_size_);
  for (const RodMap& m : rods_)
    for (int j = 0; j < m.to_points; ++j) {
      auto point = out.segment(m.to_offset + j * m.point_size, m.point_size);
      for (int k = 0; k < m.from_points; ++k)
        point += m.interpolation(j, k) * from_x.segment(m.from_offset + k * m.point_size, m.point_size);
    }
  for (const BlockCopy& c : copies_) out.segment(c.to_offset, c.size) = from_x.segment(c.from_offset, c.size);
  return out;
}

const CoarseMesh* SharedCoarseMesh::get(const FkModel& fine) {
  std::call_once(built_, [&] {
    const RobotAssembly& fa = *fine.assembly;
    if (fine.options.solver != SolverKind::Newton) return;
    for (int i = 0; i < fa.num_rods(); ++i)
      if (fa.rod_contact(i)) return;
    AssemblyOptions o = fa.options();
    o.discretization.degree = kCoarseDegree;
    o.discretization.elements = kCoarseElements;
    std::shared_ptr<const RobotAssembly> ca;
    try {
      ca = std::make_shared<const RobotAssembly>(fa.model_ptr(), o);
    } catch (const InputError&) {
      return;  // e.g. a rod the coarse discretisation does not fit: no coarse stage
    }
    if (ca->problem().num_variables() > kCoarseMaxVariableShare * fa.problem().num_variables()) return;
    auto mesh = std::make_unique<CoarseMesh>();
    mesh->to_fine = MeshTransfer(*ca, fa);
    mesh->to_coarse = MeshTransfer(fa, *ca);
    if (!mesh->to_fine.valid() || !mesh->to_coarse.valid()) return;
    mesh->weights = continuation_weights(*ca);
    auto coarse = std::make_shared<FkModel>(std::move(ca), fine.options);
    coarse->coarse_mesh = nullptr;  // no coarser stage below this one
    mesh->model = std::move(coarse);
    mesh_ = std::move(mesh);
  });
  return mesh_.get();
}

void solve_coarse_default_equilibrium(const FkModel& fine, SolveSummary& work) {
  const CoarseMesh* mesh = fine.coarse_mesh ? fine.coarse_mesh->get(fine) : nullptr;
  if (!mesh) return;
  bool solved_here = false;
  const DefaultEquilibrium& d = mesh->model->default_equilibrium(&solved_here);
  if (!solved_here) return;
  work.iterations += d.summary.iterations;
  work.jacobian_evaluations += d.summary.jacobian_evaluations;
}

std::shared_ptr<SharedCoarseMesh> new_shared_coarse_mesh() {
  return std::make_shared<SharedCoarseMesh>();
}

namespace {

/// The coarse start at u0: the coarse default equilibrium (x_from == nullptr), the coarse equilibrium
/// behind x_from when the last coarse stage returned it, else x_from carried to the coarse mesh and
/// solved there by Newton. Empty when there is none.
VecX coarse_start(const CoarseMesh& mesh, CoarseStage& stage, const VecX& u0, const VecX* x_from,
                  CoarseOutcome& out) {
  if (!x_from) {
    bool solved_here = false;
    const DefaultEquilibrium& d = mesh.model->default_equilibrium(&solved_here);
    if (solved_here) {
      out.iterations += d.summary.iterations;
      out.jacobian_evaluations += d.summary.jacobian_evaluations;
    }
    if (!d.converged) out.stopped = "the coarse mesh's default equilibrium did not converge";
    return d.converged ? d.x : VecX();
  }
  if (stage.data.has_solution && stage.fine_result.size() == x_from->size() && stage.fine_result == *x_from)
    return stage.data.x;
  // The same curves on the coarse mesh are not its equilibrium (its discretisation error, a few mm of
  // platform position): a short Newton there, with the budget of the one on the requested mesh.
  VecX xc = mesh.to_coarse.apply(*x_from);
  const SolveSummary s = stage.data.solve_at(u0, xc, kFineNewtonJacobians, true);
  out.iterations += s.iterations;
  out.jacobian_evaluations += s.jacobian_evaluations;
  if (s.converged()) return xc;
  out.stopped = "Newton on the coarse mesh at the start: " + s.message;
  return VecX();
}

/// Newton on the requested mesh at `inputs` from the coarse equilibrium xc; on success the stage keeps xc
/// behind the result (x).
void finish_on_fine_mesh(FkData& data, const CoarseMesh& mesh, CoarseStage& stage, VecX& xc,
                         const VecX& inputs, VecX& x, CoarseOutcome& out) {
  VecX xf = mesh.to_fine.apply(xc);
  out.last = data.solve_at(inputs, xf, stage.fine_jacobians);
  out.iterations += out.last.iterations;
  out.jacobian_evaluations += out.last.jacobian_evaluations;
  out.fine_jacobians = out.last.jacobian_evaluations;
  if (!out.last.converged()) {
    out.stopped = "Newton on the requested mesh from the coarse equilibrium: " + out.last.message;
    return;
  }
  stage.data.x = std::move(xc);
  stage.data.has_solution = true;
  stage.fine_result = xf;
  x = std::move(xf);
  out.converged = true;
}

CoarseStage* stage_of(FkData& data, const CoarseMesh*& mesh) {
  mesh = data.model->coarse_mesh ? data.model->coarse_mesh->get(*data.model) : nullptr;
  if (!mesh) return nullptr;
  if (!data.coarse) data.coarse = std::make_shared<CoarseStage>(mesh->model);
  return data.coarse.get();
}

}  // namespace

bool has_coarse_mesh(const FkData& data) {
  return data.model->coarse_mesh && data.model->coarse_mesh->get(*data.model) != nullptr;
}

CoarseOutcome coarse_direct(FkData& data, CoarseStart start, const VecX* x_from, const VecX& inputs, VecX& x,
                            int coarse_jacobians) {
  CoarseOutcome out;
  const CoarseMesh* mesh = nullptr;
  CoarseStage* stage = stage_of(data, mesh);
  if (!stage) return out;
  VecX xc;
  if (start == CoarseStart::FineState) {
    xc = mesh->to_coarse.apply(*x_from);
  } else if (start == CoarseStart::StraightGuess) {
    xc = mesh->model->assembly->initial_guess();
  } else {
    bool solved_here = false;
    const DefaultEquilibrium& d = mesh->model->default_equilibrium(&solved_here);
    if (solved_here) {
      out.iterations += d.summary.iterations;
      out.jacobian_evaluations += d.summary.jacobian_evaluations;
    }
    if (!d.converged) {
      out.stopped = "the coarse mesh's default equilibrium did not converge";
      return out;
    }
    xc = d.x;
  }
  out.last = stage->data.solve_at(inputs, xc, coarse_jacobians, true);
  out.iterations += out.last.iterations;
  out.jacobian_evaluations += out.last.jacobian_evaluations;
  if (!out.last.converged()) {
    out.stopped = "Newton on the coarse mesh: " + out.last.message;
    return out;
  }
  finish_on_fine_mesh(data, *mesh, *stage, xc, inputs, x, out);
  return out;
}

CoarseOutcome coarse_then_fine(FkData& data, const VecX& u0, const VecX* x_from, const VecX& inputs, VecX& x,
                               const CoarseContinuation& continuation) {
  CoarseOutcome out;
  const CoarseMesh* mesh = nullptr;
  CoarseStage* stage = stage_of(data, mesh);
  if (!stage) return out;  // stopped empty: not tried
  VecX xc = coarse_start(*mesh, *stage, u0, x_from, out);
  if (xc.size() == 0) return out;
  const ContinuationResult r = continuation(stage->data, mesh->weights, u0, xc);
  out.steps = r.steps;
  out.iterations += r.iterations;
  out.jacobian_evaluations += r.jacobian_evaluations;
  out.last = r.last;
  if (!r.converged) {
    out.stopped = "the coarse-mesh continuation stopped at " + r.stopped_at;
    return out;
  }
  // The coarse equilibrium on the requested mesh, then Newton there (the inputs as they are).
  finish_on_fine_mesh(data, *mesh, *stage, xc, inputs, x, out);
  return out;
}

}  // namespace pcr::kinematics

// Usage texts of the solve commands (pcr fk|ik|path|workspace --help); docs/cli.md says more.
#include "cli_arguments.hpp"

namespace pcr_app {
namespace {

void print_command_line(std::ostream& out, const std::string& command) {
  if (command == "fk") {
    out << "usage: pcr fk MODEL [--input NAME=VALUE ...] [--solver newton|ipopt] [--link NAME ...] "
           "[options]\n"
        << "  forward kinematics: inputs not given take the model's defaults (SI: m, rad)\n";
  } else if (command == "ik") {
    out << "usage: pcr ik MODEL --target LINK=x,y,z[,qw,qx,qy,qz] [--orientation-only LINK=qw,qx,qy,qz] ...\n"
        << "  inverse kinematics: position target (3 numbers, m) or pose target (7 numbers: position and\n"
        << "  unit quaternion w,x,y,z, normalised); --input NAME=VALUE sets the starting inputs\n";
  } else if (command == "path") {
    out << "usage: pcr path MODEL (--inputs FILE.csv | --targets FILE.csv) [options]\n"
        << "  forward kinematics along the rows of --inputs (header: input names; inputs not in it take\n"
        << "  --input NAME=VALUE or the model's defaults) or inverse kinematics along the rows of --targets\n"
        << "  (header: LINK.x, LINK.y, LINK.z and/or LINK.qw, LINK.qx, LINK.qy, LINK.qz; a position\n"
        << "  component is targeted when its column is there; --input sets the first point's reference),\n"
        << "  warm-started from point to point; one row per point: a table on stdout, --csv FILE,\n"
        << "  --json / --json-file FILE (each point as pcr fk / pcr ik write it); a progress bar on a "
           "terminal\n";
  } else {
    out << "usage: pcr workspace MODEL --samples N [--threads T] [--seed S] [options]\n"
        << "  N random inputs, uniform within the model's bounds (sample k's from (S, k) alone, default S "
           "1),\n"
        << "  each solved by forward kinematics (Newton) from the model's initial guess in T threads\n"
        << "  (default 1); results do not depend on T; summary on stdout, a progress bar on a terminal\n"
        << "  --csv FILE, --json / --json-file FILE   every sample (failed ones with their status)\n"
        << "  --png FILE         the reached platform positions: 3-D cloud and projections (gnuplot)\n";
  }
  if (command == "ik" || command == "path")
    out << "  --components LINK=x,y,z,rx,ry,rz   the target components to meet (x, y, z: world position;\n"
        << "                     rx, ry, rz: rotation about the target frame's axes), e.g. x,z,ry on a "
           "planar\n"
        << "                     robot; a target with more rows than the robot has inputs is refused\n"
        << "  --objective distance|effort|energy   what the inputs minimise among those reaching the\n"
        << "                     targets: distance to the starting inputs (default), actuation effort\n"
        << "                     (squared axial forces of the fed rods at their feed points) or the\n"
        << "                     elastic energy of all rods\n"
        << "  --max-stress PA    limit on every rod's outer-fibre stress |N|/A + |M_perp| c/I [Pa]\n";
  if (command != "workspace")
    out << "  --link NAME        also report the pose of link NAME (target links that are not platforms\n"
        << "                     are reported anyway)\n";
}

}  // namespace

void print_solve_usage(std::ostream& out, const std::string& command) {
  print_command_line(out, command);
  out << "options:\n"
      << "  --degree P --elements E --formulation auto|mixed|condensed|primal   discretisation of rods\n"
      << "                     without model hints (auto, the default: primal only for thick rods,\n"
      << "                     d/L >= 1/4, else mixed solved in the condensed form: n, m from the\n"
      << "                     closed-form balance; mixed keeps the mixed unknowns)\n"
      << "  --mixed-points midpoints|greville   where the mixed form collocates its field equations\n"
      << "                     (default midpoints; greville: the published scheme, docs/design.md)\n"
      << "  --tolerance T      max-abs of the dimensionless residuals (default 1e-10); a looser T saves\n"
      << "                     iterations, e.g. for many solves along a path: on the teleoperation\n"
      << "                     robot (R5b) the solver added about 1e-2 T m to the inputs (docs/cli.md)\n";
  if (command == "fk" || command == "path")
    out << "  --contact-method semismooth|ipopt   contact solver (docs/contact.md): semismooth Newton\n"
        << "                     (default) or Ipopt with the complementarity relaxed (Scholtes)\n";
  if (command != "workspace")
    out << "  --points N         centerline points per rod in the results (default 21)\n";
  if (command == "path")
    out << "  --folds stop|snap  along --inputs: pseudo-arclength continuation from point to point, which\n"
        << "                     passes folds (limit points); each fold is reported (path parameter,\n"
        << "                     inputs, unstable modes on both sides); stop: the points past it fail (the\n"
        << "                     branch ends); snap: the path follows the stable equilibrium the robot\n"
        << "                     snaps to and reports the jump; bifurcations are reported too\n";
  if (command != "workspace")
    out << "  --stability        stability verdict of the result: stable, or unstable with the number\n"
        << "                     of unstable modes, and a margin (costs about one more cold solve)\n";
  else
    out << "  --stability        stability verdict of every converged sample (in the CSV and JSON; the\n"
        << "                     summary counts them)\n";
  out << "  --json             JSON to stdout instead of the table\n"
      << "  --json-file FILE   JSON to FILE (the table is still printed)\n";
  if (command == "fk" || command == "ik")
    out << "  --csv DIR          DIR/summary.csv (status, stability), platforms.csv, inputs.csv,\n"
           "                     rod_<name>.csv (obstacles.csv, contacts.csv)\n"
        << "  --vtk FILE         legacy VTK polydata (rods, outlines, obstacles, contact forces) for "
           "ParaView\n"
        << "  --png FILE         3-D picture drawn by gnuplot\n";
  if (command == "path") out << "  --csv FILE         one row per point\n";
  out << "exit codes: 0 converged, 1 solve failed ("
      << (command == "fk" || command == "ik" ? "" : "at some point; ")
      << "the outputs are still written), 2 bad usage or input (also an element\n"
      << "                     count whose rods could not fit in memory), 3 an output could not be written,\n"
      << "                     4 out of memory or an internal error (a message on stderr)\n";
}

}  // namespace pcr_app

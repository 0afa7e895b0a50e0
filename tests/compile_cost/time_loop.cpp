// The shortest honest time-loop program (docs/contributing.md, compile cost): a wheelset
// contact model with one named solver, evaluated along a few poses, the step status
// checked. Built with -DFASTNORM_ANY_SOLVER it names AnySolver instead, which compiles
// every solver. tests/compile_cost/check_compile_cost.py compiles it against a budget; the
// CTest run also links and runs it.
#include <fastnorm/fastnorm.hpp>

#include <cmath>
#include <cstdio>

namespace wr = fastnorm::wheelrail;

#ifdef FASTNORM_ANY_SOLVER
using Solver = fastnorm::AnySolver<>;
#else
using Solver = fastnorm::NormSolver<>;
#endif

int main() {
  wr::WheelsetContactOptions options;
  options.grid.elements = 20;
  wr::WheelsetContact<Solver> contact(wr::Track(), wr::Wheelset(), options);
  const auto start = wr::rigid_contact_pose(contact.track(), contact.wheelset(), 0, 0);
  for (int step = 0; step < 5; ++step) {
    auto pose = start;
    pose.y = 1e-3 * std::sin(0.1 * step);
    pose.z += 0.1e-3;
    const auto& result = contact.evaluate(pose);
    if (!result.ok()) {
      std::fprintf(stderr, "step %d: %s\n", step, result.status.message.c_str());
      return 1;
    }
    std::printf("step %d: vertical force %.1f N\n", step, -result.force.z());
  }
  return 0;
}

// The yardstick of the compile-cost budgets (docs/contributing.md, compile cost): Eigen's
// dense module and its FFT, which every fastnorm program includes, and nothing of fastnorm.
// A budget is a multiple of this translation unit's compiler CPU on the same machine, so
// that a slower machine does not fail it.
#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>

int main() { return 0; }

// The start-up floor of a C++ executable: an empty main linked with
// libstdc++ (iostream's static initialisation included). Baseline of
// seaplan-bench-startup.
#include <iostream>

int main() {
  std::cout << std::flush;
  return 0;
}

// seaplan-mission-gen [--domain fjord|fjord-fuel] [--ships 3] [--ports 12]
// [--containers 12] [--seed 1] [--nearest-routes 3] [-o FILE]
//
// Writes one generated fjord mission (a PDDL problem for
// examples/fjord/domain.pddl or domain-fuel.pddl) to FILE or stdout.
#include <fstream>
#include <iostream>
#include <string>

#include "CLI/CLI.hpp"
#include "fjord_mission.h"

int main(int argc, char** argv) {
  seaplan::bench::FjordMissionSpec spec;
  std::string domain = "fjord", output;
  CLI::App app{"Generate a fjord mission (PDDL problem) scaled up from examples/fjord"};
  app.add_option("--domain", domain, "fjord (domain.pddl) or fjord-fuel (domain-fuel.pddl)")
      ->check(CLI::IsMember({"fjord", "fjord-fuel"}))
      ->capture_default_str();
  app.add_option("--ships", spec.ships, "Ships")->capture_default_str();
  app.add_option("--ports", spec.ports, "Ports")->capture_default_str();
  app.add_option("--containers", spec.containers, "Containers")->capture_default_str();
  app.add_option("--seed", spec.seed, "Seed")->capture_default_str();
  app.add_option("--nearest-routes", spec.nearest_routes, "Routes from each port to its nearest")
      ->capture_default_str();
  app.add_option("-o,--output", output, "Write the problem here (default: stdout)");
  CLI11_PARSE(app, argc, argv);
  spec.domain = domain == "fjord-fuel" ? seaplan::bench::FjordDomain::kFjordFuel
                                       : seaplan::bench::FjordDomain::kFjord;
  auto text = seaplan::bench::GenerateFjordMission(spec);
  if (!text.ok()) {
    std::cerr << "seaplan-mission-gen: " << text.status().message() << "\n";
    return 2;
  }
  if (output.empty()) {
    std::cout << *text;
    return 0;
  }
  std::ofstream out(output, std::ios::binary);
  out << *text;
  if (!out.flush()) {
    std::cerr << "seaplan-mission-gen: cannot write " << output << "\n";
    return 1;
  }
  return 0;
}

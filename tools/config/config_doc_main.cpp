// mmh-config-doc: prints docs/configuration.md (generated from the key registry), writes it, or
// checks that the checked-in page is the one the registry generates.
#include <fstream>
#include <iostream>
#include <sstream>

#include "config_reference.hpp"
#include "mmh/common/cli.hpp"

int main(int argc, char** argv) {
  std::string output, check;
  mmh::ArgParser parser("mmh-config-doc",
                        "Generates the configuration reference (Markdown) from the key registry.");
  parser.addString("--output", &output, "write the page to this file (default: standard output)");
  parser.addString("--check", &check,
                   "compare this file with the generated page; exit 1 when it differs");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  const std::string page = mmh::configReferenceMarkdown();
  if (!check.empty()) {
    std::ifstream in(check);
    std::stringstream current;
    current << in.rdbuf();
    if (in && current.str() == page) return 0;
    std::cerr << "mmh-config-doc: " << check
              << " is not what the key registry generates; regenerate it with\n"
                 "  build/bin/mmh-config-doc --output docs/configuration.md\n";
    return 1;
  }
  if (output.empty()) {
    std::cout << page;
    return 0;
  }
  std::ofstream out(output);
  out << page;
  if (!out) {
    std::cerr << "mmh-config-doc: cannot write " << output << "\n";
    return 1;
  }
  return 0;
}

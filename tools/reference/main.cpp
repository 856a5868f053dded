// Prints docs/catalogue.md (scripts/reference.sh writes it into the repository).
#include <iostream>

#include "reference/Catalogue.h"

int main() {
  std::cout << gbx::reference::catalogueMarkdown();
  return 0;
}

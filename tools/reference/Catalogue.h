#pragma once
// The catalogue's reference page (docs/catalogue.md), written from the catalogue itself:
// every stage kind, attribute, setting and effect parameter with its unit, meaning,
// default, bounds and an example. A test compares the committed page with this text.
#include <string>

namespace gbx::reference {

std::string catalogueMarkdown();

} // namespace gbx::reference

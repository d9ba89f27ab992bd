// The configuration reference (docs/configuration.md) as Markdown, generated from the key
// registry and the constraints so that the page cannot drift from what the services accept.
#pragma once

#include <string>

namespace mmh {

std::string configReferenceMarkdown();

}  // namespace mmh

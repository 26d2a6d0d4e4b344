// The preview's page (host/preview/page.html, embedded at build time so the executable needs no
// files beside it): plain HTML, CSS and JavaScript, no build step, nothing fetched from elsewhere.
#pragma once

#include <string>

namespace clmarch {

const std::string& preview_page();

}  // namespace clmarch

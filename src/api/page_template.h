// meshsal (internal): a page template's placeholders filled in (write_view_page's
// web/page.html).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace meshsal {

// `page` with each occurrence of each placeholder (a key such as "@TITLE@") replaced by its
// value, in one pass from the start: what a value holds is never searched again, so a
// model named "@BUNDLE@.glb" stays that text in its title. Throws Error when a key does not
// occur in `page` (a template out of step with its filler).
std::string fill_template(const std::string& page, const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace meshsal

// meshsal (internal): fill_template (page_template.h).
#include "api/page_template.h"

#include "meshsal/meshsal.h"

namespace meshsal {

std::string fill_template(const std::string& page, const std::vector<std::pair<std::string, std::string>>& values) {
  std::vector<bool> used(values.size(), false);
  std::string out;
  size_t at = 0;
  for (size_t mark; (mark = page.find('@', at)) != std::string::npos;) {
    out.append(page, at, mark - at);
    size_t k = 0;
    while (k < values.size() &&
           (values[k].first.empty() || page.compare(mark, values[k].first.size(), values[k].first) != 0))
      ++k;
    if (k == values.size()) {  // an @ of the page's own text
      out += '@';
      at = mark + 1;
    } else {
      out += values[k].second;
      used[k] = true;
      at = mark + values[k].first.size();
    }
  }
  out.append(page, at, std::string::npos);
  for (size_t k = 0; k < values.size(); ++k)
    if (!used[k]) throw Error("the page template has no placeholder " + values[k].first);
  return out;
}

}  // namespace meshsal

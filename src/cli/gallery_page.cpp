// meshsal batch --html: the gallery page (gallery_page.h).
#include "gallery_page.h"

#include <cctype>
#include <cstdio>
#include <string>

#include "core/html_text.h"
#include "io/atomic_write.h"

namespace meshsal::cli {
namespace {

using meshsal::html_escaped;

// A relative link to a file beside the gallery: its name, percent-encoded where a URL needs it.
std::string href(const std::string& name) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '.' || c == '_' || c == '-' || c == '~') out += char(c);
    else out += '%', out += hex[c >> 4], out += hex[c & 15];
  }
  return out;
}

}  // namespace

void write_gallery(const std::string& path, const std::vector<GalleryItem>& items) {
  size_t done = 0;
  for (const GalleryItem& it : items) done += it.status == "done" && !it.page.empty();
  std::string html =
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"generator\" content=\"meshsal\">\n"
      "<title>meshsal batch: " + std::to_string(items.size()) + " models</title>\n<style>\n"
      "body { font: 14px/1.4 system-ui, sans-serif; margin: 16px; color: #222; }\n"
      ".grid { display: flex; flex-wrap: wrap; gap: 12px; }\n"
      ".card { width: 220px; border: 1px solid #ccc; border-radius: 4px; padding: 6px; background: #fafafa; }\n"
      ".card img { width: 220px; height: 220px; object-fit: contain; background: #fff; display: block; }\n"
      ".card .name { margin-top: 4px; word-break: break-all; }\n"
      ".card.failed { border-color: #c33; background: #fde; }\n"
      ".card.skipped { border-color: #c90; background: #fff4d6; }\n"
      ".card .why { font-size: 12px; color: #633; word-break: break-word; }\n"
      "</style>\n</head>\n<body>\n<h1>meshsal batch: " + std::to_string(items.size()) + " models</h1>\n"
      "<p>" + std::to_string(done) + " with a page: click a picture to turn the model in the browser.</p>\n"
      "<div class=\"grid\">\n";
  for (const GalleryItem& it : items) {
    if (!it.page.empty()) {
      html += "<div class=\"card done\"><a href=\"" + href(it.page) + "\"><img src=\"" + href(it.picture) + "\" alt=\"" +
              html_escaped(it.name) + "\"></a><div class=\"name\"><a href=\"" + href(it.page) + "\">" + html_escaped(it.name) +
              "</a></div></div>\n";
    } else {
      html += "<div class=\"card " + html_escaped(it.status) + "\"><div class=\"name\">" + html_escaped(it.name) + ": " +
              html_escaped(it.status) + "</div><div class=\"why\">" + html_escaped(it.message) + "</div></div>\n";
    }
  }
  html += "</div>\n</body>\n</html>\n";
  meshsal::write_file_atomically(path, [&](std::FILE* f) { meshsal::write_all(f, html.data(), html.size(), path); });
}

}  // namespace meshsal::cli

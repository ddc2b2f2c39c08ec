// Issue 21 (7): what the CLI prints stays valid JSON (every --json object, the batch log)
// and safe on a terminal, whatever bytes a file name holds (cli/json_string.h).
#include <catch2/catch.hpp>

#include <string>

#include "cli/json_string.h"

using meshsal::cli::json_string;
using meshsal::cli::printable;

TEST_CASE("json_string: quotes, controls and bytes that are not UTF-8 are escaped", "[cli]") {
  CHECK(json_string("plain/path.obj") == "\"plain/path.obj\"");
  CHECK(json_string("say \"hi\"\\") == "\"say \\\"hi\\\"\\\\\"");
  CHECK(json_string("a\nb\tc\x1b") == "\"a\\u000ab\\u0009c\\u001b\"");
  CHECK(json_string("del\x7f") == "\"del\\u007f\"");
  CHECK(json_string("c1 \xc2\x9b") == "\"c1 \\u009b\"");           // U+009B, a CSI to some terminals
  CHECK(json_string("caf\xc3\xa9 \xe2\x82\xac") == "\"caf\xc3\xa9 \xe2\x82\xac\"");  // UTF-8 kept
  CHECK(json_string("caf\xe9") == "\"caf\\udce9\"");               // Latin-1 byte: surrogate escape
  CHECK(json_string("\xc0\xaf") == "\"\\udcc0\\udcaf\"");          // overlong '/'
  CHECK(json_string("\xed\xa0\x80") == "\"\\udced\\udca0\\udc80\"");  // an encoded surrogate
  CHECK(json_string("\xe2\x82") == "\"\\udce2\\udc82\"");          // cut short
  CHECK(json_string("\xf4\x90\x80\x80") == "\"\\udcf4\\udc90\\udc80\\udc80\"");  // above U+10FFFF
  CHECK(json_string(std::string("nul\0x", 5)) == "\"nul\\u0000x\"");
}

TEST_CASE("printable: one line, no escape sequences, UTF-8 names untouched", "[cli]") {
  CHECK(printable("scans/bunny.ply") == "scans/bunny.ply");
  CHECK(printable("caf\xc3\xa9.obj") == "caf\xc3\xa9.obj");
  CHECK(printable("two\nlines") == "two\\x0alines");
  CHECK(printable("\x1b]0;title\x07") == "\\x1b]0;title\\x07");
  CHECK(printable("\xc2\x9b" "31m") == "\\xc2\\x9b31m");
  CHECK(printable("caf\xe9") == "caf\\xe9");
  CHECK(printable("tab\there") == "tab\\x09here");
}

TEST_CASE("json_string and printable: bidirectional controls are escaped, other UTF-8 kept", "[cli]") {
  // U+202E RIGHT-TO-LEFT OVERRIDE would show "evil<RLO>gnp.obj" as "evilobj.png".
  CHECK(json_string("evil\xe2\x80\xaegnp.obj") == "\"evil\\u202egnp.obj\"");
  CHECK(printable("evil\xe2\x80\xaegnp.obj") == "evil\\u202egnp.obj");
  CHECK(json_string("\xd8\x9c\xe2\x80\x8e\xe2\x80\x8f\xe2\x81\xa6\xe2\x81\xa9") ==
        "\"\\u061c\\u200e\\u200f\\u2066\\u2069\"");
  CHECK(printable("\xe2\x80\xaa\xe2\x80\xad") == "\\u202a\\u202d");
  CHECK(json_string("\xe2\x80\x8b\xe2\x80\xaf") == "\"\xe2\x80\x8b\xe2\x80\xaf\"");  // U+200B, U+202F: not bidi
  CHECK(printable("\xe2\x81\xa5\xe2\x81\xaa") == "\xe2\x81\xa5\xe2\x81\xaa");         // U+2065, U+206A
}

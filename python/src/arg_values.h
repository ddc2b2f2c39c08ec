// meshsal Python module: numbers and sequences from arguments, with the module's one rule
// for their errors: a wrong type is TypeError (a bool or a str for a number, an array where
// one value belongs, bytes or a 0-d array where a sequence belongs), a value out of range
// ValueError naming the value. pybind11's own casts are not used for them: an int beyond
// C++'s range raised RuntimeError there, and True was taken for 1.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

namespace meshsal_py {

namespace py = pybind11;

// An integer in [lo, hi]: a Python int, a numpy integer or anything with __index__ (a 0-d
// integer array too), not a bool or a float. `name` starts the messages.
long long integer_arg(const py::handle& value, const char* name, long long lo, long long hi);
// The same for the unsigned C++ counts (seeds, byte sizes), up to 2^64 - 1.
uint64_t unsigned_arg(const py::handle& value, const char* name, uint64_t lo, uint64_t hi);

// True for a whole number by type: a Python int (not a bool) or a numpy integer (a 0-d
// integer array too). How an argument that takes counts and ratios tells them apart.
bool is_integer(const py::handle& value);

// An integer in [0, 2^32 - 1], the library's unsigned counts (threads, tiles; the
// library has its own limits on them).
unsigned count_arg(const py::handle& value, const char* name);

// A real number: an int, a float, a numpy scalar or a 0-d array; not a bool, a str or an
// array of values. Not checked for range (the caller's rule), but one beyond a double's
// range (10**400) is ValueError.
double number_arg(const py::handle& value, const char* name);

// The items of a sequence argument, each held as an owned reference (an item a numpy array,
// a range or a generator makes lives only as long as someone holds it): a list, a tuple, a
// range, a 1-D array, a generator or any other iterable. TypeError "NAME must be EXPECTED,
// got TYPE" for a str or bytes (a sequence of characters, not of values), a 0-d array, a
// dict or anything not iterable. Reads at most limit + 1 items, so that an endless
// generator ends and the caller can say "at most limit".
std::vector<py::object> sequence_items(const py::handle& value, const char* name, const char* expected,
                                       size_t limit);

// The Python type's name, for messages ("int", "numpy.ndarray" as "ndarray").
std::string type_name(const py::handle& value);

}  // namespace meshsal_py

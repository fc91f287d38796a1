#pragma once
// The header of a PCD file, checked before PCL reads it. PCL's reader believes what a header
// announces: it allocates POINTS × the point size of that moment while it parses, matches
// statements by prefix ("WIDTHS" is WIDTH to it), lets a repeated statement override the first and
// reads on after DATA while lines look like statements. A header passes this check only when PCL
// and scanloc read it alike and the file can hold the points it announces.

#include <string>

namespace scanloc {

// Throws ParseError (file, line, what was expected) unless the header of the PCD at `path` is one
// known statement per line, none repeated, with no statement after DATA, and the points it
// announces fit in the bytes after it.
void CheckPcdHeader(const std::string& path);

}  // namespace scanloc

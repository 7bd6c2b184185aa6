// Reads and writes per-face labels as a text file: one integer per face, in
// face order (0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = unlabelled; docs/design.md section
// 3.1). Plain text so labels can be made by any script and fixed by hand.
#pragma once

#include <string>
#include <vector>

namespace polycube {

// Values are separated by any whitespace; '#' starts a comment to the end of
// the line. Throws Error with one sentence naming the path (and line) on a
// missing file, a non-integer, a value outside -1..5, or a count different
// from face_count.
std::vector<int> read_labels(const std::string& path, int face_count);

// The same over bytes in memory (the fuzz target); path names them in messages.
std::vector<int> parse_labels(const std::string& path, const std::string& data, int face_count);

// How a labels file starts: with a comment line stating the convention (read
// back by read_labels, which skips comments), or plain, nothing but the
// integers, for tools that take every token for a label (docs/design.md
// section 3.1).
enum class LabelsHeader { kComment, kPlain };

// One label per line; atomic like write_mesh. Throws Error if a value is
// outside -1..5 or the file cannot be written.
void write_labels(const std::string& path, const std::vector<int>& labels,
                  LabelsHeader header = LabelsHeader::kComment);

// The text write_labels would write (for OutputFiles::stage); the same errors.
std::string labels_file_text(const std::string& path, const std::vector<int>& labels,
                             LabelsHeader header = LabelsHeader::kComment);

}  // namespace polycube

// mfv check: the reader of the user's files. A C tokenizer (comments, string
// and character literals, line splices, numbers, identifiers) and the
// preprocessor's conditional compilation (#if/#ifdef/#elif/#else/#endif over
// the file's own #defines and --define), so that the contract's functions
// and `// mfv: param` lines are found where the compiler would see them: a
// `/* */` comment, a string, a macro or an `#if 0` changes nothing
// (docs/cli/check.md "How the file is read").
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mfv {

struct Token {
  enum Kind { Ident, Number, String, Char, Punct, LineComment, BlockComment, Directive } kind;
  size_t begin = 0, end = 0;  // offsets into the text [begin, end)
  int line = 1;               // line of its first character
  std::string text;           // the token's text with line splices removed
};

// The tokens of `text`, comments and whole directive lines included. Throws
// mfv::Error naming `path` and the line for an unterminated comment, string
// or character literal.
std::vector<Token> tokenize(const std::string& path, const std::string& text);

// One file as the compiler reads it.
struct ReadUnit {
  std::string path, text;
  // `text` with comments, literals' contents, directive lines and the
  // branches that conditional compilation drops blanked to spaces (newlines
  // kept: offsets and lines are those of `text`).
  std::string code;
  std::vector<Token> tokens;  // of `text`, each with active = in a branch the compiler keeps
  std::vector<bool> active;
  std::vector<std::pair<int, std::string>> mfv_lines;  // (line, body) of active `// mfv: BODY` comments
  std::vector<std::pair<int, std::string>> includes;   // (line, resolved path) of active #include "FILE"
};

struct ReadOptions {
  std::map<std::string, std::string> defines;  // --define NAME=VALUE (and the build's own)
  std::vector<std::string> includes;           // --include FILE: read first, in order
};

struct ReadSources {
  std::vector<ReadUnit> units;  // every file, in the order the compiler reads them
  std::vector<size_t> top;      // the --include files, then the main file (top.back())
};

// Reads `path` after the --include files, following `#include "FILE"`
// (relative to the including file) in active branches. #if on a name that
// is not defined is an error (as -Werror=undef), naming the file, the line
// and --define. Throws mfv::Error (one line) on any fault.
ReadSources read_sources(const std::string& path, const ReadOptions& opt);

// The text the compiler reads for unit `at`: texts[at] (the unit's text, or
// its translation with the same lines) with each active `#include` line
// replaced by the included unit's text between #line markers.
std::string with_includes(const std::vector<ReadUnit>& units, const std::vector<std::string>& texts, size_t at);

int line_of(const std::string& text, size_t pos);

}  // namespace mfv

/* The -options_file chain, checked before PetscInitialize() reads it.

   PETSc reads an -options_file found inside an options file at once, recursively, with no check for a
   cycle: a file that names itself, directly or through another file, recurses until the stack
   overflows, a segmentation fault inside PetscInitialize(). The driver first follows the chain as text
   the way PETSc reads it (per line, '#' starts a comment, whitespace separates the words, a relative
   name is relative to the working directory, not to the file), from the command line and the
   PETSC_OPTIONS variable, and stops at a cycle, at a chain deeper than any scene needs, or at a file
   that cannot be opened, with a message naming the files. */
#include "driver.h"
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace {

const size_t max_depth = 16; /* scenes include one or two files; 16 is far beyond any real need */

/* the words of options text, without comments; quotes around a word are removed */
std::vector<std::string> Words(const std::string &text)
{
  std::vector<std::string> words;
  std::istringstream       lines(text);
  std::string              line;
  while (std::getline(lines, line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream in(line);
    std::string        w;
    while (in >> w) {
      if (w.size() >= 2 && (w.front() == '"' || w.front() == '\'') && w.back() == w.front()) w = w.substr(1, w.size() - 2);
      words.push_back(w);
    }
  }
  return words;
}

std::string Chain(const std::vector<std::string> &chain, const std::string &last)
{
  std::string s;
  for (const std::string &f : chain) s += f + " -> ";
  return s + last;
}

/* Follow the -options_file words of `words`; chain holds the names of the files being read (as given),
   paths their canonical paths. Returns false with *message set at the first problem. */
bool Follow(const std::vector<std::string> &words, std::vector<std::string> &chain, std::vector<std::string> &paths, std::string *message)
{
  for (size_t i = 0; i + 1 < words.size(); i++) {
    if (words[i] != "-options_file") continue;
    std::string name = words[i + 1];
    if (name.find('$') != std::string::npos) continue; /* PETSc substitutes ${PETSC_DIR} and the like: left to PETSc */
    if (name.compare(0, 2, "~/") == 0 && getenv("HOME")) name = std::string(getenv("HOME")) + name.substr(1);
    const std::string where = chain.empty() ? std::string("") : " (named in " + chain.back() + ")";
    char              real[PATH_MAX];
    if (!realpath(name.c_str(), real)) {
      *message = "-options_file " + words[i + 1] + ": cannot open: " + strerror(errno) + where;
      return false;
    }
    for (size_t k = 0; k < paths.size(); k++)
      if (paths[k] == real) {
        *message = "-options_file cycle: " + Chain(chain, words[i + 1]) + " (" + chain.back() + " names a file that is being read; remove that -options_file line)";
        return false;
      }
    if (chain.size() >= max_depth) {
      *message = "-options_file chain deeper than " + std::to_string(max_depth) + " files: " + Chain(chain, words[i + 1]);
      return false;
    }
    std::ifstream in(name);
    if (!in) {
      *message = "-options_file " + words[i + 1] + ": cannot open: " + strerror(errno) + where;
      return false;
    }
    std::stringstream text;
    text << in.rdbuf();
    chain.push_back(words[i + 1]);
    paths.push_back(real);
    if (!Follow(Words(text.str()), chain, paths, message)) return false;
    chain.pop_back();
    paths.pop_back();
    i++;
  }
  return true;
}

} // namespace

/* true when the -options_file chain of the command line and of PETSC_OPTIONS can be read; otherwise
   false and *message names the files (a cycle, a chain too deep, a file that does not open) */
bool DriverCheckOptionsFiles(int argc, char **argv, std::string *message)
{
  std::vector<std::string> words, chain, paths;
  for (int i = 1; i < argc; i++) words.push_back(argv[i]);
  if (!Follow(words, chain, paths, message)) return false;
  if (const char *env = getenv("PETSC_OPTIONS")) {
    if (!Follow(Words(env), chain, paths, message)) {
      *message += " (from the PETSC_OPTIONS variable)";
      return false;
    }
  }
  return true;
}

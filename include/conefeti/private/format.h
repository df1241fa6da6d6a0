/* printf into a std::string, for messages built in pieces (the scene's and the mesh reader's errors) */
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

static inline std::string ConeFETIFormat(const char *fmt, ...)
{
  va_list ap, again;
  va_start(ap, fmt);
  va_copy(again, ap);
  const int   n = vsnprintf(nullptr, 0, fmt, ap);
  std::string s(n > 0 ? (size_t)n : 0, '\0');
  if (n > 0) vsnprintf(&s[0], (size_t)n + 1, fmt, again);
  va_end(again);
  va_end(ap);
  return s;
}

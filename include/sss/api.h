/* sss/api.h — SSS_API, the mark on every function (and datum) that libsss.so exports.
 *
 * The library is compiled with -fvisibility=hidden, so only what the public headers declare with
 * SSS_API is visible to programs linking libsss.so; the modules' internal helpers stay inside it,
 * where they can change between versions and cannot clash with a program's symbols. A test checks
 * the exported set against the declarations of the headers in include/sss, both ways
 * (tests/install/check_exports.py; docs/versioning.md, "The exported surface"). With a compiler other
 * than GCC or Clang, SSS_API is empty.
 */
#ifndef SSS_API_H
#define SSS_API_H

#if defined(__GNUC__) /* GCC and Clang */
#define SSS_API __attribute__((visibility("default")))
#else
#define SSS_API
#endif

#endif

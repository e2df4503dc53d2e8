# Run after lcm-gen -x (cmake -DDIRECTORY=<dir of .hpp> -P harden_decoders.cmake):
# makes the generated C++ decoders refuse length fields no encoder writes,
# since every message we decode comes from the network or a log file.
#
# lcm-gen 1.3.1 checks a string's length prefix only against the bytes
# left: a length of 0 or less reaches std::string::assign(p, length - 1),
# which throws for most values and overflows (undefined behaviour, then a
# read of 2 GiB past the buffer) for INT32_MIN; bytes after an embedded NUL
# are kept in the string. A variable array's count is not checked at all
# before the vector is resized to it. Found by the fuzz targets (tests/fuzz,
# regressions/*/zero_length_string, negative_string_length and
# embedded_nul_in_client). Every encoded string has at least its NUL byte,
# and every array element at least one byte, which gives the bounds.

file(GLOB headers "${DIRECTORY}/*.hpp")
foreach(header IN LISTS headers)
  file(READ "${header}" text)
  # The string's bytes must also be a C string: its first NUL is its last
  # byte. LCM's encoders write strlen() + 1 bytes, so an embedded NUL is
  # malformed, and a string kept with one would not encode to the size
  # getEncodedSize() announces (an ack echoing it would be garbled).
  string(REGEX REPLACE
    "if\\(__([A-Za-z0-9_]+)_len__ > maxlen - pos\\) return -1;"
    "if(__\\1_len__ <= 0 || __\\1_len__ > maxlen - pos ||\n       memchr((const char*)buf + offset + pos, 0, __\\1_len__) !=\n           (const char*)buf + offset + pos + __\\1_len__ - 1) return -1;"
    text "${text}")
  # The same for each string of a string array (robot_command_t.joint_names:
  # a length of INT32_MIN overflowed in `__elem_len - 1`, fuzz_robot_command_message).
  string(REGEX REPLACE
    "if\\(__elem_len > maxlen - pos\\) return -1;"
    "if(__elem_len <= 0 || __elem_len > maxlen - pos ||\n           memchr((const char*)buf + offset + pos, 0, __elem_len) !=\n               (const char*)buf + offset + pos + __elem_len - 1) return -1;"
    text "${text}")
  string(REGEX REPLACE
    "this->([A-Za-z0-9_]+)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
    "if(this->\\2 < 0 || this->\\2 > maxlen - pos) return -1;\n    this->\\1.resize(this->\\2);"
    text "${text}")
  # A different lcm-gen would slip through unhardened: stop the build instead.
  if(text MATCHES "if\\(__[A-Za-z0-9_]+_len__ > maxlen - pos\\)" OR text MATCHES "if\\(__elem_len > maxlen - pos\\)")
    message(FATAL_ERROR "harden_decoders: an unguarded string length remains in ${header}")
  endif()
  file(WRITE "${header}" "${text}")
endforeach()

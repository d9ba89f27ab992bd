# Hardens the decoders lcm-gen writes (run after lcm-gen on every header in DIR).
#
# lcm-gen 1.3.1 sizes an array from its length field before it reads the data, so a 40-byte
# message claiming 2^31 floats makes the receiver allocate and zero 8 GB; and a string length of
# 0 or INT32_MIN turns `len - 1` into a huge size or a signed overflow. Each array length is now
# checked against the bytes left (every element takes at least one byte) and each string length
# must be at least 1 (its terminating NUL). A failed check makes decode() return -1 like any
# other malformed buffer.
if(NOT DIR)
  message(FATAL_ERROR "guard_decode.cmake: -DDIR=<folder of generated headers> is required")
endif()
file(GLOB headers ${DIR}/*.hpp)
foreach(header ${headers})
  file(READ ${header} text)
  string(REGEX REPLACE
    "if\\(([A-Za-z0-9_]+) > maxlen - pos\\) return -1;"
    "if(\\1 < 1 || \\1 > maxlen - pos) return -1;"
    text "${text}")
  string(REGEX REPLACE
    "( *)this->([A-Za-z0-9_]+)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
    "\\1if(this->\\3 < 0 || this->\\3 > maxlen - pos) return -1;\n\\1this->\\2.resize(this->\\3);"
    text "${text}")
  file(WRITE ${header} "${text}")
endforeach()

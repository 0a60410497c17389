// SPDX-License-Identifier: MIT
// For the tests of .npy files: a reader written from the NPY format specification
// (numpy.lib.format) independently of tessera's writer, strict about every byte of the header,
// and Debian's numpy to read them too.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace tessera::npy_test {

struct NpyArray {
  std::string descr;  ///< '<f8' or '<i8'
  bool fortran_order = true;
  std::int64_t rows = -1;  ///< shape (rows, columns)
  std::int64_t columns = -1;
  std::size_t data_offset = 0;
  std::vector<double> reals;           ///< descr '<f8', C order
  std::vector<std::int64_t> integers;  ///< descr '<i8', C order
};

// Reads `path`, failing the test (and returning what it has) on any departure from version 1.0
// of the format as tessera promises to write it: 2-d, C order, little endian, aligned to 64.
inline NpyArray read_npy(const std::string& path) {
  NpyArray array;
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  EXPECT_GE(bytes.size(), 10u) << path;
  if (bytes.size() < 10) {
    return array;
  }
  EXPECT_EQ(bytes.substr(0, 6), std::string("\x93NUMPY")) << path;
  EXPECT_EQ(bytes[6], 1) << "major version, " << path;
  EXPECT_EQ(bytes[7], 0) << "minor version, " << path;
  const std::size_t header_length =
      static_cast<unsigned char>(bytes[8]) + 256u * static_cast<unsigned char>(bytes[9]);
  array.data_offset = 10 + header_length;
  EXPECT_EQ(array.data_offset % 64, 0u) << "the data must start at a multiple of 64, " << path;
  EXPECT_LE(array.data_offset, bytes.size()) << path;
  if (array.data_offset > bytes.size()) {
    return array;
  }
  const std::string header = bytes.substr(10, header_length);
  EXPECT_EQ(header.back(), '\n') << path;
  // The dictionary, then spaces only.
  const std::size_t end = header.find('}');
  EXPECT_NE(end, std::string::npos) << header;
  EXPECT_EQ(header.find_first_not_of(' ', end + 1), header.size() - 1) << header;
  const std::string dictionary = header.substr(0, end + 1);
  const auto value_after = [&](const std::string& key) {
    const std::size_t at = dictionary.find("'" + key + "': ");
    EXPECT_NE(at, std::string::npos) << key << " in " << dictionary;
    return at == std::string::npos ? std::string() : dictionary.substr(at + key.size() + 4);
  };
  const std::string descr = value_after("descr");
  array.descr = descr.substr(1, descr.find('\'', 1) - 1);
  array.fortran_order = value_after("fortran_order").rfind("True", 0) == 0;
  const std::string shape = value_after("shape");
  EXPECT_EQ(std::sscanf(shape.c_str(), "(%ld, %ld)", &array.rows, &array.columns), 2) << shape;
  EXPECT_FALSE(array.fortran_order) << dictionary;
  const std::size_t count = static_cast<std::size_t>(array.rows * array.columns);
  EXPECT_EQ(bytes.size() - array.data_offset, 8 * count) << "data size, " << path;
  if (bytes.size() - array.data_offset != 8 * count) {
    return array;
  }
  static_assert(std::endian::native == std::endian::little, "the test reader reads '<' arrays");
  // (memcpy from an empty vector's null data() is undefined even for 0 bytes.)
  if (array.descr == "<f8") {
    array.reals.resize(count);
    if (count > 0) {
      std::memcpy(array.reals.data(), bytes.data() + array.data_offset, 8 * count);
    }
  } else if (array.descr == "<i8") {
    array.integers.resize(count);
    if (count > 0) {
      std::memcpy(array.integers.data(), bytes.data() + array.data_offset, 8 * count);
    }
  } else {
    ADD_FAILURE() << "descr '" << array.descr << "' in " << path;
  }
  return array;
}

// The first of $TESSERA_PYTHON, /usr/bin/python3 and python3 that can import numpy (a python3
// of pyenv or a virtualenv may not see Debian's packages), or "" if none can.
inline std::string python_with_numpy() {
  std::vector<std::string> candidates;
  if (const char* configured = std::getenv("TESSERA_PYTHON")) {
    candidates.emplace_back(configured);
  }
  candidates.insert(candidates.end(), {"/usr/bin/python3", "python3"});
  for (const auto& python : candidates) {
    if (std::system((python + " -c 'import numpy' >/dev/null 2>&1").c_str()) == 0) {
      return python;
    }
  }
  return "";
}

// Output (stdout and stderr) and exit status of `python -c script arguments…`. The script may not
// contain double quotes; the arguments no single quotes.
inline std::pair<std::string, int> run_python(const std::string& python, const std::string& script,
                                              const std::vector<std::string>& arguments) {
  std::string command = python + " -c \"" + script + "\"";
  for (const auto& argument : arguments) {
    command += " '" + argument + "'";
  }
  command += " 2>&1";
  std::string output;
  int status = -1;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
      output.append(buffer, count);
    }
    status = pclose(pipe);
  }
  return {output, status};
}

}  // namespace tessera::npy_test

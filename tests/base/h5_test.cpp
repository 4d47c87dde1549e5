// SPDX-License-Identifier: MIT
#include "base/h5.h"

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "base/error.h"

TEST_CASE("h5: round trip of datasets, strings and attributes") {
  auto path = std::filesystem::temp_directory_path() / "pastemix_h5_test.h5";
  {
    pastemix::H5Writer w(path);
    std::vector<double> grid{1, 2, 3, 4, 5, 6};
    w.write("/cases/3/C", grid, {2, 3});
    std::vector<std::int64_t> ids{7, 8};
    w.write("/ids", ids);
    w.write_strings("/names", {"M_111", "M_211"});
    w.attribute("/", "seed", std::int64_t{42});
    w.attribute("/cases/3/C", "unit", "percent");
    w.attribute("/cases", "K", 3570.0);
  }
  pastemix::H5Reader r(path);
  CHECK(r.exists("/cases/3/C"));
  CHECK_FALSE(r.exists("/cases/4/C"));
  CHECK(r.dims("/cases/3/C") == std::vector<std::uint64_t>{2, 3});
  CHECK(r.read_doubles("/cases/3/C")[5] == 6.0);
  CHECK(r.read_ints("/ids")[1] == 8);
  CHECK(r.read_strings("/names")[1] == "M_211");
  CHECK(r.attribute_int("/", "seed") == 42);
  CHECK(r.attribute_string("/cases/3/C", "unit") == "percent");
  CHECK(r.attribute_double("/cases", "K") == 3570.0);
  CHECK_THROWS_AS(r.read_doubles("/nope"), pastemix::InputError);
  std::filesystem::remove(path);
}

TEST_CASE("h5: a file that is not HDF5 is an input error") {
  auto path = std::filesystem::temp_directory_path() / "pastemix_not_h5.h5";
  { std::FILE* f = std::fopen(path.c_str(), "w"); std::fputs("hello", f); std::fclose(f); }
  CHECK_THROWS_AS(pastemix::H5Reader{path}, pastemix::InputError);
  std::filesystem::remove(path);
}

TEST_CASE("h5: a write the disk refuses is an input error naming the file, not an abort") {
  // RLIMIT_FSIZE makes the kernel refuse writes past 64 KB with EFBIG, as a full disk refuses them with
  // ENOSPC; with SIGXFSZ ignored, write() returns the error to HDF5. (Before: an uncaught H5::Exception,
  // exit 134.)
  const auto path = std::filesystem::temp_directory_path() / fmt::format("pastemix_h5_full_{}.h5", ::getpid());
  rlimit old{};
  REQUIRE(::getrlimit(RLIMIT_FSIZE, &old) == 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 64 * 1024;
  REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string message;
  try {
    pastemix::H5Writer h5(path);
    h5.write("/big", std::vector<double>(100000, 1.0));  // 800 KB
    h5.close();
  } catch (const pastemix::InputError& e) {
    message = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  std::filesystem::remove(path);
  CHECK(message.find(path.string()) == 0);
  CHECK(message.find("cannot write") != std::string::npos);
}

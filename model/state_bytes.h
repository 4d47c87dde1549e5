// SPDX-License-Identifier: MIT
// The engine's dynamic state as raw bytes (model/checkpoint.cpp, and the flow coupling's own part,
// fluid/flow_coupling.cpp): each trivially copyable member, and each vector with its length, in a fixed order,
// so that the doubles come back bit for bit (no text round trip). A reader names the file it reads on damage.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "base/error.h"

namespace pastemix::model {

class StateBytes {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* b = reinterpret_cast<const char*>(&v);
    buf_.insert(buf_.end(), b, b + sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(v.size()));
    const auto* b = reinterpret_cast<const char*>(v.data());
    buf_.insert(buf_.end(), b, b + v.size() * sizeof(T));
  }
  void put(const std::vector<bool>&) = delete;
  const std::vector<char>& data() const { return buf_; }

 private:
  std::vector<char> buf_;
};

class StateReader {
 public:
  StateReader(std::span<const std::uint8_t> data, std::string path) : data_(data), path_(std::move(path)) {}
  template <class T>
  void get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&v, sizeof(T));
  }
  template <class T>
  void get(std::vector<T>& v) {
    std::uint64_t n = 0;
    get(n);
    if (n > (data_.size() - at_) / std::max<std::size_t>(sizeof(T), 1)) damaged("a length past the end");
    v.resize(n);
    take(v.data(), n * sizeof(T));
  }
  bool done() const { return at_ == data_.size(); }
  [[noreturn]] void damaged(const std::string& why) const {
    throw InputError(path_, 0, "/checkpoint/state", fmt::format("damaged checkpoint ({}): start the run again", why));
  }

 private:
  void take(void* out, std::size_t n) {
    if (n > data_.size() - at_) damaged("truncated");
    std::memcpy(out, data_.data() + at_, n);
    at_ += n;
  }
  std::span<const std::uint8_t> data_;
  std::string path_;
  std::size_t at_ = 0;
};

}  // namespace pastemix::model

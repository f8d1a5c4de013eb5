// SHA-256 of a stream of bytes (OpenSSL's), for fingerprints a reader compares: not a signature (cache_signer.h
// signs with a key).
#pragma once

#include <memory>
#include <string>
#include <string_view>

namespace ipd {

class Sha256 {
 public:
  Sha256();  // throws std::runtime_error when OpenSSL has no SHA-256
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(std::string_view bytes);
  std::string hex();  // the digest in lower-case hex; ends the stream

 private:
  struct Context;
  std::unique_ptr<Context> ctx_;
};

}  // namespace ipd

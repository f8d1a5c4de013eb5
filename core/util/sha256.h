// SHA-256 of a stream of bytes (OpenSSL's), for fingerprints a reader compares: not a signature (cache_signer.h
// signs with a key).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace ipd {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(std::string_view bytes);
  std::string hex();  // the digest in lower-case hex; ends the stream

  // The running state after the bytes added so far, as opaque bytes: a stream resumed from it (resume()) and
  // given the rest ends in the same digest as one given every byte. For caches this installation signs.
  std::string state() const;
  // The stream `state` was taken from; nullopt when `state` is not one (another size or an impossible count).
  static std::optional<Sha256> resume(std::string_view state);
  Sha256(Sha256&&) noexcept;
  Sha256& operator=(Sha256&&) noexcept;

 private:
  struct Context;
  std::unique_ptr<Context> ctx_;
};

}  // namespace ipd

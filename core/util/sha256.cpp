#include "core/util/sha256.h"

// The one-call SHA-256 functions are deprecated in OpenSSL 3 in favour of EVP, whose state can't be taken
// out and put back; the running state is what a fingerprint resumed from a cache needs.
#define OPENSSL_SUPPRESS_DEPRECATED
#include <openssl/sha.h>

#include <fmt/format.h>
#include <cstring>
#include <stdexcept>

namespace ipd {

struct Sha256::Context {
  SHA256_CTX ctx;
};

Sha256::Sha256() : ctx_(std::make_unique<Context>()) {
  if (!SHA256_Init(&ctx_->ctx)) throw std::runtime_error("SHA-256 failed");
}

Sha256::~Sha256() = default;
Sha256::Sha256(Sha256&&) noexcept = default;
Sha256& Sha256::operator=(Sha256&&) noexcept = default;

void Sha256::add(std::string_view bytes) {
  if (!SHA256_Update(&ctx_->ctx, bytes.data(), bytes.size())) throw std::runtime_error("SHA-256 failed");
}

std::string Sha256::hex() {
  unsigned char out[SHA256_DIGEST_LENGTH];
  if (!SHA256_Final(out, &ctx_->ctx)) throw std::runtime_error("SHA-256 failed");
  std::string s;
  for (unsigned char c : out) s += fmt::format("{:02x}", c);
  return s;
}

std::string Sha256::state() const { return std::string(reinterpret_cast<const char*>(&ctx_->ctx), sizeof(SHA256_CTX)); }

std::optional<Sha256> Sha256::resume(std::string_view state) {
  if (state.size() != sizeof(SHA256_CTX)) return std::nullopt;
  Sha256 s;
  std::memcpy(&s.ctx_->ctx, state.data(), sizeof(SHA256_CTX));
  // Fewer bytes buffered than a block and a 32-byte digest, or it is no SHA-256 state.
  if (s.ctx_->ctx.num >= SHA256_CBLOCK || s.ctx_->ctx.md_len != SHA256_DIGEST_LENGTH) return std::nullopt;
  return s;
}

}  // namespace ipd

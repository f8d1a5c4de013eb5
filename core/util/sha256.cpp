#include "core/util/sha256.h"

#include <openssl/evp.h>

#include <fmt/format.h>
#include <stdexcept>

namespace ipd {

struct Sha256::Context {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  ~Context() { EVP_MD_CTX_free(ctx); }
};

Sha256::Sha256() : ctx_(std::make_unique<Context>()) {
  if (!ctx_->ctx || !EVP_DigestInit_ex(ctx_->ctx, EVP_sha256(), nullptr))
    throw std::runtime_error("SHA-256 is not available from OpenSSL");
}

Sha256::~Sha256() = default;

void Sha256::add(std::string_view bytes) {
  if (!EVP_DigestUpdate(ctx_->ctx, bytes.data(), bytes.size())) throw std::runtime_error("SHA-256 failed");
}

std::string Sha256::hex() {
  unsigned char out[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!EVP_DigestFinal_ex(ctx_->ctx, out, &len)) throw std::runtime_error("SHA-256 failed");
  std::string s;
  for (unsigned int i = 0; i < len; ++i) s += fmt::format("{:02x}", out[i]);
  return s;
}

}  // namespace ipd

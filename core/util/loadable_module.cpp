#include "core/util/loadable_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace ipd {

namespace {

std::vector<std::filesystem::path> module_dirs() {
  namespace fs = std::filesystem;
  std::vector<fs::path> dirs;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back((exe.parent_path() / IPD_MODULES_FROM_BIN).lexically_normal());
    dirs.push_back(exe.parent_path());
  }
  dirs.emplace_back(IPD_BUILD_MODULE_DIR);
  return dirs;
}

}  // namespace

void* open_module(const std::string& file_name) {
  static std::mutex mutex;
  static std::map<std::string, void*> opened;  // never closed: their code may run until exit
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = opened.find(file_name); it != opened.end()) return it->second;
  std::string looked, reason;
  for (const auto& dir : module_dirs()) {
    const std::filesystem::path p = dir / file_name;
    looked += (looked.empty() ? "" : ", ") + p.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) continue;
    if (void* handle = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL)) return opened[file_name] = handle;
    if (const char* e = dlerror()) reason = std::string(": ") + e;
  }
  throw std::runtime_error("cannot open the module " + file_name + " (looked for " + looked + ")" + reason);
}

void* module_symbol(void* module, const std::string& file_name, const char* symbol) {
  void* p = dlsym(module, symbol);
  if (!p) throw std::runtime_error("the module " + file_name + " has no " + symbol + " (from another version?)");
  return p;
}

}  // namespace ipd

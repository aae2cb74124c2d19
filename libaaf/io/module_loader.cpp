// Finds and loads aaf's run-time modules (module_loader.h).
#include "module_loader.h"

#include <dlfcn.h>

#include <filesystem>
#include <vector>

#include "aaf/core/util/error.h"

namespace aaf::io {

namespace {

/// Folders to look in, in order: the folder of the executable or library
/// that holds this code (dladdr), the install layout's library folder
/// relative to it (bin/ -> lib/, and lib/pythonX.Y/site-packages/ -> lib/),
/// then this build's and the install prefix's library folders.
std::vector<std::filesystem::path> module_folders() {
    std::vector<std::filesystem::path> folders;
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void *>(&load_module_table), &info) && info.dli_fname) {
        const std::filesystem::path here = std::filesystem::path(info.dli_fname).parent_path();
        folders.push_back(here);
        folders.push_back(here / AAF_MODULES_BIN_TO_LIB);
        folders.push_back(here / ".." / "..");
    }
    folders.emplace_back(AAF_MODULES_BUILD_DIR);
    folders.emplace_back(AAF_MODULES_INSTALL_DIR);
    return folders;
}

}  // namespace

const void *load_module_table(const char *file, const char *entry, const char *purpose) {
    std::string why = "not found";
    for (const std::filesystem::path &folder : module_folders()) {
        std::error_code error;
        const std::filesystem::path path = folder / file;
        if (!std::filesystem::is_regular_file(path, error)) continue;
        void *handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char *message = dlerror();
            why = message ? message : "cannot be loaded";
            continue;
        }
        using Entry = const void *(*)();
        if (const auto function = reinterpret_cast<Entry>(dlsym(handle, entry))) return function();
        why = path.string() + " has no " + entry;
    }
    throw Error(std::string(file) + ": cannot load aaf's module for " + purpose + ": " + why +
                "; it belongs beside the aaf executable or in the install's lib folder");
}

}  // namespace aaf::io

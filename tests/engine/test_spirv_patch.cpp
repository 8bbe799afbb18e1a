// The denormal-keeping edit of a SPIR-V module (host/vk/spirv_patch.h), made for GPUs that offer
// it: every kernel's patched module passes spirv-val and carries DenormPreserve 32 on its entry
// point, and nothing else of the module changes.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "kernel_ids.h"
#include "vk/embedded_shaders.h"
#include "vk/spirv_patch.h"

namespace fs = std::filesystem;
using namespace repose;

TEST_CASE("a kernel with denormals kept is valid SPIR-V that says so", "[engine][vulkan]") {
  fs::path dir = fs::temp_directory_path() / "repose_test_spirv_patch";
  fs::create_directories(dir);
  for (uint32_t k = 0; k < static_cast<uint32_t>(KernelId::Count); ++k) {
    const char* name = kernel_shader_name(static_cast<KernelId>(k));
    const vk::EmbeddedShader& spv = vk::embedded_shader(name);
    std::vector<uint32_t> patched = vk::with_denormals_preserved(spv.words, spv.bytes / 4);
    // Three instructions added: the capability (2 words), the extension (7) and the mode (4).
    CHECK(patched.size() == spv.bytes / 4 + 13);
    fs::path file = dir / (std::string(name) + ".spv");
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(patched.data()), patched.size() * 4);
    INFO(name);
    CHECK(std::system(("spirv-val --target-env vulkan1.2 " + file.string()).c_str()) == 0);
    std::string listing = (dir / (std::string(name) + ".txt")).string();
    REQUIRE(std::system(("spirv-dis " + file.string() + " -o " + listing).c_str()) == 0);
    std::ifstream in(listing);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    CHECK(text.find("OpCapability DenormPreserve") != std::string::npos);
    CHECK(text.find("OpExtension \"SPV_KHR_float_controls\"") != std::string::npos);
    CHECK(text.find("OpExecutionMode %main DenormPreserve 32") != std::string::npos);
  }
  uint32_t not_spirv[6] = {1, 2, 3, 4, 5, 6};
  CHECK_THROWS(vk::with_denormals_preserved(not_spirv, 6));
}

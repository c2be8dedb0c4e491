// kernels/abi/integral.h is one layout for kernels and host: the device's
// sizeof(IntegralSpec) and every field's offset equal the host compiler's,
// and the header reaches the kernels through `#include "abi/..."` from the
// embedded sources and from --kernel-dir alike.
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "runtime/integrator.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

using namespace mfv;

namespace {

// Every field of IntegralSpec, once, in declaration order (p: the array's first element).
#define MFV_SPEC_FIELDS(X)                                                                                    \
  X(check) X(model) X(estimator) X(channel) X(d) X(g) X(f) X(pd) X(pg) X(pd2) X(pg2) X(f0) X(f1) X(kd) X(p) \
      X(eta) X(side) X(bsdf) X(lobe) X(cos_o) X(phi_o) X(width) X(width_y) X(stream) X(stream_hi) X(strata) X(points)

struct Field {
  const char* name;
  size_t offset, size;
};
#define MFV_FIELD(name) {#name, offsetof(IntegralSpec, name), sizeof(IntegralSpec::name)},
const std::vector<Field> kFields = {MFV_SPEC_FIELDS(MFV_FIELD)};
#undef MFV_FIELD

// A kernel (an extra source, so that the include is expanded there too) that
// writes sizeof(IntegralSpec), then each field's offset, in kFields' order.
std::string offsets_kernel() {
  std::string body;
  for (size_t i = 0; i < kFields.size(); ++i)
    body += fmt::format("  out[{}] = (uint)((__global const char*)&s->{} - b);\n", i + 1, kFields[i].name);
  return "#include \"abi/integral.h\"\n"
         "__kernel void abi_offsets(__global const IntegralSpec* s, __global uint* out) {\n"
         "  __global const char* b = (__global const char*)s;\n"
         "  out[0] = (uint)sizeof(IntegralSpec);\n" +
         body + "}\n";
}

std::vector<cl_uint> device_offsets(Runtime& rt) {
  cl::Program prog = rt.build({"common.cl"}, {}, "", "", {{"abi_test.cl", offsets_kernel(), ""}});
  cl::Kernel k(prog, "abi_offsets");
  IntegralSpec spec;
  cl::Buffer sb(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof spec, &spec);
  std::vector<cl_uint> out(kFields.size() + 1, 0xffffffffu);
  cl::Buffer ob(rt.context(), CL_MEM_WRITE_ONLY, out.size() * sizeof(cl_uint));
  k.setArg(0, sb);
  k.setArg(1, ob);
  rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  rt.queue().enqueueReadBuffer(ob, CL_TRUE, 0, out.size() * sizeof(cl_uint), out.data());
  return out;
}

void check_layout(const std::vector<cl_uint>& dev) {
  CHECK(dev[0] == sizeof(IntegralSpec));
  for (size_t i = 0; i < kFields.size(); ++i) {
    CAPTURE(kFields[i].name);
    CHECK(dev[i + 1] == kFields[i].offset);
  }
}

}  // namespace

TEST_CASE("The offset test lists every field of IntegralSpec once, with no gap", "[abi]") {
  // fields in declaration order tile the struct: a field left out of the list leaves a gap
  size_t at = 0;
  for (const Field& f : kFields) {
    CAPTURE(f.name);
    CHECK(f.offset == at);
    at = f.offset + f.size;
  }
  CHECK(at == sizeof(IntegralSpec));
}

TEST_CASE("IntegralSpec has the same size and field offsets on the device as on the host", "[device][abi]") {
  Runtime* rt = test::device_runtime();
  if (!rt) return;
  check_layout(device_offsets(*rt));
}

TEST_CASE("The shared layout header is read from --kernel-dir as the kernel files are", "[device][abi]") {
  if (!test::device_runtime()) return;
  test::PlantedKernelDir dir;
  Runtime rt = dir.runtime();
  check_layout(device_offsets(rt));
  // a field moved in the folder's header moves on the device: the header is read from there
  REQUIRE(dir.replace("abi/integral.h", "  mfv_i32 check MFV_INIT(0);      /* MFV_CHECK_* */\n", ""));
  REQUIRE(dir.replace("abi/integral.h", "  mfv_u32 points MFV_INIT(0);",
                      "  mfv_u32 points MFV_INIT(0);\n  mfv_i32 check MFV_INIT(0);"));
  const std::vector<cl_uint> moved = device_offsets(rt);
  CHECK(moved[1] == sizeof(IntegralSpec) - 4);  // check is now the last field
}

// list_devices, find_device and names_device (include/snapfit/devices.h) against the
// enumeration and selection they wrap (engine/runtime/device.h).
#include <doctest/doctest.h>

#include "engine/runtime/device.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("list_devices: every device in enumeration order, the default selected, each self-check passed") {
  const test::EnvScope no_env("SNAPFIT_DEVICE", nullptr);
  const std::vector<Device> devices = enumerate_devices();
  REQUIRE(!devices.empty());
  std::vector<DeviceInfo> infos;
  for (const Device& d : devices) infos.push_back(d.info);
  const std::size_t chosen = select_device_index(infos, "");

  DeviceListRequest request;
  request.check = true;
  const DeviceList list = list_devices(request);
  REQUIRE(list.devices.size() == devices.size());
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const ListedDevice& d = list.devices[i];
    CAPTURE(d.info.name);
    CHECK(d.info.index == devices[i].info.index);
    CHECK(d.info.name == devices[i].info.name);
    CHECK(d.selected == (i == chosen));
    REQUIRE(d.checks.size() == (d.info.fp64 ? 2u : 1u));
    CHECK(d.checks[0].precision == "float");
    for (const DeviceCheck& c : d.checks) {
      CHECK(c.passed);
      CHECK(c.relative_error <= c.tolerance);
      CHECK((c.program == "compiled" || c.program == "cache hit" || c.program == "recompiled (bad cache entry)"));
    }
  }
  CHECK(list_devices().devices.front().checks.empty());  // no checks unless asked
}

TEST_CASE("find_device: the spec's device, the default for an empty one, a named error for none") {
  const test::EnvScope no_env("SNAPFIT_DEVICE", nullptr);
  const std::vector<Device> devices = enumerate_devices();
  std::vector<DeviceInfo> infos;
  for (const Device& d : devices) infos.push_back(d.info);
  CHECK(find_device("").index == static_cast<int>(select_device_index(infos, "")));
  CHECK(find_device("0").name == devices[0].info.name);
  CHECK_THROWS_AS(find_device("no device is called this"), Error);
  CHECK(!describe_device(find_device("")).empty());
}

TEST_CASE("names_device: the spec, else $SNAPFIT_DEVICE") {
  const test::EnvScope no_env("SNAPFIT_DEVICE", nullptr);
  CHECK(!names_device(""));
  CHECK(names_device("cpu"));
  const test::EnvScope env("SNAPFIT_DEVICE", "0");
  CHECK(names_device(""));
}

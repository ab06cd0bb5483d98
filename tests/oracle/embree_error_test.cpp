// Embree's errors reach the caller as EmbreeError (issue 30): the device's callback, which runs
// inside Embree's C code, only records them, and the wrappers throw after the call. Also the
// oracle's preconditions a library caller can get wrong are std::invalid_argument, not an abort.
#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "embree/embree_handles.h"
#include "oracle/accel.h"
#include "oracle/oracle.h"
#include "test_scenes.h"

namespace so::test {
namespace {

// Embree asks before each allocation; false makes it fail the operation with
// RTC_ERROR_OUT_OF_MEMORY, as a real allocation failure would.
bool refuseMemory(void*, ssize_t bytes, bool) {
    return bytes <= 0;
}

TEST(EmbreeErrors, OutOfMemoryReachesTheCaller) {
    EmbreeDevice device("threads=1");
    rtcSetDeviceMemoryMonitorFunction(device.get(), refuseMemory, nullptr);
    const Scene scene = makeSquareOccluderScene(32, 24).scene;
    try {
        Accel accel(scene, device);
        FAIL() << "the build should have run out of memory";
    } catch (const EmbreeError& e) {
        EXPECT_EQ(e.code(), int(RTC_ERROR_OUT_OF_MEMORY));
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("Embree error 4: ", 0), 0u) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        std::printf("[ embree ] %s\n", what.c_str());
    }
    // The error was taken: the device works again once memory is there.
    rtcSetDeviceMemoryMonitorFunction(device.get(), nullptr, nullptr);
    EXPECT_NO_THROW(device.throwIfError());
    EXPECT_NO_THROW(Accel(scene, device));
}

TEST(EmbreeErrors, InvalidCallsThrowFromTheWrapper) {
    EmbreeDevice device("threads=1");
    EmbreeGeometry g(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Float indices are no index buffer Embree knows.
    EXPECT_THROW(g.newBuffer(RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_FLOAT3, 12, 1), EmbreeError);
    // A call made on the raw handle is recorded until asked for, then forgotten.
    rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_FLOAT3, 12, 1);
    EXPECT_THROW(device.throwIfError(), EmbreeError);
    EXPECT_NO_THROW(device.throwIfError());
}

TEST(EmbreeErrors, BadDeviceConfigurationThrows) {
    EXPECT_THROW(EmbreeDevice("isa=not_an_isa,threads=x"), EmbreeError);
}

TEST(OracleErrors, CallerPreconditionsAreInvalidArgument) {
    EXPECT_THROW(tileRows(64, 3, 3), std::invalid_argument);
    EXPECT_THROW(tileRows(64, 0, 17), std::invalid_argument) << "64 rows are 16 tile rows";
    const Scene scene = makeSquareOccluderScene(32, 24).scene;
    OracleOptions o;
    o.rows = RowBand{2, 8};  // not a multiple of the tile height
    EXPECT_THROW(runOracle(scene, o), std::invalid_argument);
}

}  // namespace
}  // namespace so::test

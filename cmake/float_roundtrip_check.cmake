# GCC 12.2 at -O2/-O3 miscompiles double -> float -> double for three coordinates in one
# expression: its SLP vectorizer keeps the first two unrounded (seen here: `D{(double)(float)x,
# (double)(float)y, (double)(float)z}` and `glm::dvec3(glm::vec3(p))` both return x and y as they
# came). The oracle's error bounds rely on that rounding (the triangle "as Embree holds it",
# oracle/offset.cpp), so a compiler with the fault gets -fno-tree-slp-vectorize for every project
# target. The check runs the pattern at the build type's optimisation level; vectorization without
# -ffast-math keeps IEEE results, so the flag changes speed, never a value.
include(CheckCXXSourceRuns)
include(CMakePushCheckState)
function(shadow_oracle_check_float_roundtrip out_target)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    return()
  endif()
  string(TOUPPER "${CMAKE_BUILD_TYPE}" build_type)
  cmake_push_check_state(RESET)
  set(CMAKE_REQUIRED_FLAGS "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${build_type}} -O2")
  check_cxx_source_runs([=[
    struct D { double x, y, z; };
    __attribute__((noinline)) D roundTrip(D p) {
        return D{(double)(float)p.x, (double)(float)p.y, (double)(float)p.z};
    }
    int main() {
        volatile double e = 1e-12;
        D r = roundTrip(D{1.0 + e, 1.0 + e, 1.0 + e});
        return (r.x == 1.0 && r.y == 1.0 && r.z == 1.0) ? 0 : 1;
    }]=] SHADOW_ORACLE_FLOAT_ROUNDTRIP_OK)
  cmake_pop_check_state()
  if(NOT SHADOW_ORACLE_FLOAT_ROUNDTRIP_OK)
    message(STATUS "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} drops a double -> float "
                   "rounding under SLP vectorization: building with -fno-tree-slp-vectorize")
    target_compile_options(${out_target} INTERFACE -fno-tree-slp-vectorize)
  endif()
endfunction()

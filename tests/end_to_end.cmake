# End-to-end tests: the round trip on the example room (always runs) and the
# reference scenes of ../shared/scenes (skipped where they are absent).
if(NOT RELIGHT_SANITIZED)
  add_executable(roundtrip_test roundtrip_test.cpp)
  target_link_libraries(roundtrip_test PRIVATE relight_relight relight_example TBB::tbb GTest::gtest_main)
  gtest_discover_tests(roundtrip_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600 LABELS slow)
endif()

if(NOT RELIGHT_SANITIZED)
  add_executable(e2e_test e2e_test.cpp)
  target_link_libraries(e2e_test PRIVATE relight_relight GTest::gtest_main)
  target_compile_definitions(e2e_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(e2e_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 1200 LABELS reference COST 100)
endif()

add_executable(cli_test cli_test.cpp)
target_link_libraries(cli_test PRIVATE relight_cli relight_example nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(cli_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}" RELIGHT_VERSION="${PROJECT_VERSION}")
gtest_discover_tests(cli_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

if(NOT RELIGHT_SANITIZED)
  add_executable(probe_lights_test probe_lights_test.cpp)
  target_link_libraries(probe_lights_test PRIVATE relight_analysis GTest::gtest_main)
  target_compile_definitions(probe_lights_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(probe_lights_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300 LABELS reference)
endif()

if(NOT RELIGHT_SANITIZED)
  add_executable(fit_test fit_test.cpp)
  target_link_libraries(fit_test PRIVATE relight_analysis GTest::gtest_main)
  target_compile_definitions(fit_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(fit_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900 LABELS reference COST 80)
endif()

# A rig's new environment on a floor under a sky.
add_executable(new_sky_test new_sky_test.cpp)
target_link_libraries(new_sky_test PRIVATE relight_relight GTest::gtest_main)
gtest_discover_tests(new_sky_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

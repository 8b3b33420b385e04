# End-to-end tests: the round trip on the example room (always runs) and the
# reference scenes of ../shared/scenes (skipped where they are absent).
relight_add_unsanitized_test(roundtrip_test roundtrip_test.cpp 600 slow relight_relight relight_example TBB::tbb)
relight_add_unsanitized_test(e2e_test e2e_test.cpp 1200 reference COST 100 relight_relight)

add_executable(cli_test cli_test.cpp)
target_link_libraries(cli_test PRIVATE relight_cli relight_example nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(cli_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}" RELIGHT_VERSION="${PROJECT_VERSION}")
gtest_discover_tests(cli_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

relight_add_unsanitized_test(probe_lights_test probe_lights_test.cpp 300 reference relight_analysis)
relight_add_unsanitized_test(fit_test fit_test.cpp 900 reference COST 80 relight_analysis)

# A rig's new environment on a floor under a sky.
add_executable(new_sky_test new_sky_test.cpp)
target_link_libraries(new_sky_test PRIVATE relight_relight GTest::gtest_main)
gtest_discover_tests(new_sky_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

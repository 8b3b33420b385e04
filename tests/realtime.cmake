# The interactive engine: the relighting session (caches, refinement, exact
# convergence to render_rig) and the OpenGL backend against the CPU one on
# the reference scenes (skipped without OpenGL or without the scenes), its
# compute and fragment shading against each other on the example room.
add_executable(session_test session_test.cpp)
target_link_libraries(session_test PRIVATE relight_relight relight_example GTest::gtest_main)
# The new sky in a view twice the photo's size (25 s under the sanitizers)
# is labelled slow: the sanitizer step runs a view of another size and the
# new sky's preview and convergence in the session's other tests.
relight_discover_tests_but_slow(session_test 600 session_test.larger_view_new_sky
                                Session.AViewOfAnotherSizeShowsTheNewSkyToo)

# An animated rig's frames (relight/frame_sequence.h).
add_executable(frame_sequence_test frame_sequence_test.cpp)
target_link_libraries(frame_sequence_test PRIVATE relight_relight relight_example GTest::gtest_main)
gtest_discover_tests(frame_sequence_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

add_executable(realtime_test realtime_test.cpp)
target_link_libraries(realtime_test PRIVATE relight_realtime relight_io relight_example GTest::gtest_main)
target_compile_definitions(realtime_test PRIVATE RELIGHT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
gtest_discover_tests(realtime_test TEST_FILTER "Scenes/*" DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 900 LABELS reference)
gtest_discover_tests(realtime_test TEST_FILTER "GlShading.*" DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# Where the shadow maps look from: geometry only, no OpenGL context needed.
relight_add_test(light_views_test light_views_test.cpp relight_realtime)
target_include_directories(light_views_test PRIVATE ${PROJECT_SOURCE_DIR}/src)

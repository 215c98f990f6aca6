pcr_add_test(NAME test_kinematics LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_kinematics.cpp
             ${CMAKE_CURRENT_LIST_DIR}/robots/test_kinematics_option_names.cpp
             ${CMAKE_CURRENT_LIST_DIR}/robots/test_solver_agreement.cpp)
pcr_add_test(NAME test_input_continuation LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_input_continuation.cpp)
pcr_add_test(NAME test_path_predictor LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_path_predictor.cpp)
pcr_add_test(NAME test_stability_monitor LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_stability_monitor.cpp)
# Two threads solving one model at once, and the start of cold FK solves shared per model (also run by
# the sanitizer pass of scripts/test.sh).
find_package(Threads REQUIRED)
pcr_add_test(NAME test_concurrent_solves LABELS robots
             SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_concurrent_solves.cpp
                     ${CMAKE_CURRENT_LIST_DIR}/robots/test_shared_cold_start.cpp LIBS Threads::Threads)
# The 6-RUS robot (models/six_rus.urdf): symmetries, round trips, mesh, their published example.
pcr_add_test(NAME test_six_rus LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_six_rus.cpp)

# Universal and revolute rod ends, passive URDF joints.
pcr_add_test(NAME test_joint_ends LABELS rods SOURCES ${CMAKE_CURRENT_LIST_DIR}/rods/test_joint_ends.cpp)
pcr_add_test(NAME test_joints LABELS robots SOURCES ${CMAKE_CURRENT_LIST_DIR}/robots/test_joints.cpp
             ${CMAKE_CURRENT_LIST_DIR}/robots/test_joint_model_checks.cpp)

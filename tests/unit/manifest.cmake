lodbake_unit_test(mesh_check_manifest_test SOURCES mesh_check_manifest_test.cpp
                  LIBS lodbake_check lodbake_meshio)
add_dependencies(mesh_check_manifest_test dragon_data)

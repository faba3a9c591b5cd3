lodbake_unit_test(mesh_check_manifest_test SOURCES mesh_check_manifest_test.cpp
                  LIBS lodbake_check lodbake_meshio)

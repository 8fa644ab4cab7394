# What a Blender user opens of a simplify result (tests/blender/open_in_blender.py): Blender's
# own importers (the pinned bpy wheel in the virtual environment .ci/setup --tests makes) and
# Cycles renders beside the reference's, labelled `blender`. Without that environment these
# tests fail, naming .ci/setup. Included by tests/CMakeLists.txt.
set(SUBDFIT_BLENDER_PYTHON "${PROJECT_SOURCE_DIR}/.tools/blender/bin/python" CACHE FILEPATH "a Python with the pinned bpy")
set(blender_quick --steps 20 --res 64 --views 4 --holdout-views 1)

# A reference with no material, heights and a normal map: no material but the one carrying the
# maps, in DCC's default grey (the decoded glb with an invented darker grey renders 21-23 dB).
add_test(NAME blender.spot
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/simplify_and_open.sh $<TARGET_FILE:subdfit> ${SUBDFIT_BLENDER_PYTHON}
                 ${CMAKE_CURRENT_BINARY_DIR}/blender/spot ${PROJECT_SOURCE_DIR}/assets/spot/spot_triangulated.obj 25 25
                 --faces 200 --maps displacement,normal ${blender_quick})
# A textured glTF reference: its base colour image (without it the decoded glb renders ~17 dB).
add_test(NAME blender.duck
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/simplify_and_open.sh $<TARGET_FILE:subdfit> ${SUBDFIT_BLENDER_PYTHON}
                 ${CMAKE_CURRENT_BINARY_DIR}/blender/duck ${PROJECT_SOURCE_DIR}/assets/gltf/Duck/Duck.glb 27 24
                 --faces 150 ${blender_quick})
set_tests_properties(blender.spot blender.duck PROPERTIES LABELS blender TIMEOUT 300)

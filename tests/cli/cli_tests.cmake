# The command line end to end (ctest -L cli): bad input files and impossible options are
# refused with one stderr line naming the culprit and leave no output folder; a short fit
# writes every result file and no temporary one. Included by tests/CMakeLists.txt.
set(SUBDFIT_CLI_SCRIPTS ${CMAKE_CURRENT_LIST_DIR})
set(SUBDFIT_CLI_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli)
set(SUBDFIT_CLI_BAD ${PROJECT_SOURCE_DIR}/tests/data/bad)
set(SUBDFIT_CLI_CAGE ${PROJECT_SOURCE_DIR}/assets/osd-shapes/catmark_torus.obj)
set(SUBDFIT_CLI_REFERENCE ${PROJECT_SOURCE_DIR}/assets/spot/spot_triangulated.obj)

# subdfit_cli_command_refuses(COMMAND NAME EXPECT ARG...): `subdfit COMMAND ARG... --out
# <build>/cli/NAME` must fail, printing one stderr line that contains EXPECT.
function(subdfit_cli_command_refuses command name expect)
  list(JOIN ARGN "|" args)
  add_test(NAME cli.refuses.${name}
           COMMAND ${CMAKE_COMMAND} -DSUBDFIT=$<TARGET_FILE:subdfit> -DOUT=${SUBDFIT_CLI_OUT}/${name}
                   -DEXPECT=${expect} -DARGS=${command}|${args} -P ${SUBDFIT_CLI_SCRIPTS}/expect_failure.cmake)
  set_tests_properties(cli.refuses.${name} PROPERTIES LABELS cli TIMEOUT 120)
endfunction()

function(subdfit_cli_refuses name expect)
  subdfit_cli_command_refuses(fit ${name} ${expect} ${ARGN})
endfunction()

# Bad cage files: the message names the file.
foreach(case
    "missing_cage|${SUBDFIT_CLI_OUT}/does_not_exist.obj"
    "truncated_obj|${SUBDFIT_CLI_BAD}/truncated.obj"
    "bad_face_entry|${SUBDFIT_CLI_BAD}/bad_face_entry.obj"
    "nan_coordinate|${SUBDFIT_CLI_BAD}/nan_coordinate.obj"
    "index_out_of_range|${SUBDFIT_CLI_BAD}/index_out_of_range.obj"
    "empty_mesh|${SUBDFIT_CLI_BAD}/empty.obj"
    "no_faces|${SUBDFIT_CLI_BAD}/no_faces.obj"
    "unknown_extension|${SUBDFIT_CLI_BAD}/mesh.txt"
    "bad_crease_tag|${SUBDFIT_CLI_BAD}/crease_out_of_range.obj"
    "gltf_index_out_of_range|${SUBDFIT_CLI_BAD}/index_out_of_range.gltf"
    "truncated_draco|${SUBDFIT_CLI_BAD}/truncated.drc")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 file)
  subdfit_cli_refuses(cage_${name} ${file} --cage ${file} --reference ${SUBDFIT_CLI_REFERENCE})
endforeach()

# A bad reference is refused the same way (a good cage does not hide it).
subdfit_cli_refuses(reference_nan_coordinate ${SUBDFIT_CLI_BAD}/nan_coordinate.obj
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_BAD}/nan_coordinate.obj)
subdfit_cli_refuses(reference_missing ${SUBDFIT_CLI_OUT}/missing_reference.obj
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_OUT}/missing_reference.obj)

# A reference that is a single point, and a cage that is all holes: refused before any fit,
# naming the file.
subdfit_cli_refuses(reference_single_point "single_point.obj: every vertex is at the same point"
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${PROJECT_SOURCE_DIR}/tests/data/bad-scenes/single_point.obj)
subdfit_cli_refuses(cage_all_holes "all_holes.obj: every face is tagged as a hole"
                    --cage ${PROJECT_SOURCE_DIR}/tests/data/bad-scenes/all_holes.obj --reference ${SUBDFIT_CLI_REFERENCE})

# Impossible options: the message names the option.
subdfit_cli_refuses(option_res_0 --res --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --res 0)
subdfit_cli_refuses(option_views_0 --views --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --views 0)
subdfit_cli_refuses(option_steps_negative --steps
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --steps -1)
subdfit_cli_refuses(option_position_bits_7 "--position-bits must be in 8..16"
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --position-bits 7)
subdfit_cli_refuses(option_tess_0 --tess --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --tess 0)
subdfit_cli_refuses(option_epsilon_0 --epsilon
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --epsilon 0)
subdfit_cli_refuses(option_maps_unknown --maps
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --maps bumps)
subdfit_cli_refuses(option_map_res_0 --map-res
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --maps displacement --map-res 0)
# Options the parser itself rejects get the same one-line treatment.
subdfit_cli_refuses(option_steps_not_a_number --steps
                    --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --steps abc)
subdfit_cli_refuses(option_usd_unknown --usd --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --usd usdc)
subdfit_cli_refuses(option_unknown --bogus --cage ${SUBDFIT_CLI_CAGE} --reference ${SUBDFIT_CLI_REFERENCE} --bogus)

# A short fit that works: every result file, nothing temporary left.
add_test(NAME cli.fit.torus_to_spot
         COMMAND ${CMAKE_COMMAND} -DSUBDFIT=$<TARGET_FILE:subdfit> -DOUT=${SUBDFIT_CLI_OUT}/fit_torus_to_spot
                 -DSTEPS=3 -DEXTRA=fitted.glb|asset.usdz
                 "-DARGS=fit|--cage|${SUBDFIT_CLI_CAGE}|--reference|${SUBDFIT_CLI_REFERENCE}|--steps|3|--res|64|--views|2|--preview"
                 -P ${SUBDFIT_CLI_SCRIPTS}/expect_success.cmake)
set_tests_properties(cli.fit.torus_to_spot PROPERTIES LABELS cli TIMEOUT 600)

# decode: anything but a whole .subd file names the file, and no .glb appears.
subdfit_cli_command_refuses(decode decode_missing missing.subd ${SUBDFIT_CLI_OUT}/missing.subd)
subdfit_cli_command_refuses(decode decode_not_subd "truncated.obj: not a .subd file" ${SUBDFIT_CLI_BAD}/truncated.obj)
subdfit_cli_command_refuses(decode decode_tess_0 --tess ${SUBDFIT_CLI_BAD}/truncated.obj --tess 0)

# simplify: a bad or missing reference names the file; impossible options name the option.
subdfit_cli_command_refuses(simplify simplify_missing_reference ${SUBDFIT_CLI_OUT}/missing.obj
                            ${SUBDFIT_CLI_OUT}/missing.obj)
subdfit_cli_command_refuses(simplify simplify_nan_reference ${SUBDFIT_CLI_BAD}/nan_coordinate.obj
                            ${SUBDFIT_CLI_BAD}/nan_coordinate.obj)
subdfit_cli_command_refuses(simplify simplify_faces_2 --faces ${SUBDFIT_CLI_REFERENCE} --faces 2)
subdfit_cli_command_refuses(simplify simplify_map_res_0 --map-res ${SUBDFIT_CLI_REFERENCE} --map-res 0)
subdfit_cli_command_refuses(simplify simplify_budget_unit "--budget: must be bytes" ${SUBDFIT_CLI_REFERENCE} --budget 20parsecs)
subdfit_cli_command_refuses(simplify simplify_budget_tiny "--budget: must be 100 bytes" ${SUBDFIT_CLI_REFERENCE} --budget 50)

# batch: the manifest is read and checked before any work; a bad line names file and line.
subdfit_cli_command_refuses(batch batch_missing_manifest ${SUBDFIT_CLI_OUT}/missing.txt ${SUBDFIT_CLI_OUT}/missing.txt)
set(SUBDFIT_CLI_MANIFESTS ${PROJECT_SOURCE_DIR}/tests/data/bad-manifests)
subdfit_cli_command_refuses(batch batch_bad_line bad_option.txt:3 ${SUBDFIT_CLI_MANIFESTS}/bad_option.txt)
subdfit_cli_command_refuses(batch batch_empty_manifest empty.txt ${SUBDFIT_CLI_MANIFESTS}/empty.txt)
subdfit_cli_command_refuses(batch batch_help_on_a_line "help_on_a_line.txt:2: --help is an option of the command line"
                            ${SUBDFIT_CLI_MANIFESTS}/help_on_a_line.txt)
subdfit_cli_command_refuses(batch batch_bad_shard --shard ${SUBDFIT_CLI_MANIFESTS}/bad_option.txt --shard 2/2)

# A short simplify that works: the fit's files plus the shipped cage, the comparison and the
# baselines (its budget behaviour: tests/gl/simplify_budget_test.cpp).
add_test(NAME cli.simplify.spot
         COMMAND ${CMAKE_COMMAND} -DSUBDFIT=$<TARGET_FILE:subdfit> -DOUT=${SUBDFIT_CLI_OUT}/simplify_spot
                 -DSTEPS=4 "-DEXTRA=asset.usdz|comparison.png|initial_cage.obj|baselines/decimated.glb|baselines/bake/asset.subd"
                 "-DARGS=simplify|${SUBDFIT_CLI_REFERENCE}|--faces|80|--steps|4|--res|48|--views|2|--holdout-views|1"
                 -P ${SUBDFIT_CLI_SCRIPTS}/expect_success.cmake)
# Its folder is also the result the viewer's tests show (tests/view/view_tests.cmake).
set_tests_properties(cli.simplify.spot PROPERTIES LABELS cli TIMEOUT 600 FIXTURES_SETUP simplify_spot)

# What that simplify shipped decodes for engines (tests/cli/decode_for_engines.sh): the default
# density, a chain of levels of detail, an error bound, bad options.
add_test(NAME cli.decode.engines
         COMMAND bash ${SUBDFIT_CLI_SCRIPTS}/decode_for_engines.sh $<TARGET_FILE:subdfit> ${SUBDFIT_CLI_OUT}/decode_engines
                 ${SUBDFIT_CLI_OUT}/simplify_spot ${SUBDFIT_CLI_REFERENCE})
set_tests_properties(cli.decode.engines PROPERTIES LABELS cli TIMEOUT 300 FIXTURES_REQUIRED simplify_spot)

# What that simplify shipped as USD opens in Pixar's USD with no validation error
# (tests/usd/read_usd.py; the usd-core environment .ci/setup makes).
add_test(NAME usd.simplify_spot
         COMMAND ${SUBDFIT_USD_PYTHON} ${PROJECT_SOURCE_DIR}/tests/usd/read_usd.py ${SUBDFIT_CLI_OUT}/simplify_spot/asset.usdz
                 ${SUBDFIT_CLI_OUT}/simplify_spot_usd --check)
set_tests_properties(usd.simplify_spot PROPERTIES LABELS "usd;cli" TIMEOUT 120 FIXTURES_REQUIRED simplify_spot)

# What a batch service meets (tests/cli/service/*.sh): manifests named to escape --out or to
# collide, two batches on one folder, SIGKILL and SIGTERM, FIFOs and devices as inputs, a
# damaged checkpoint, --out folders that must not be used.
foreach(script hostile_manifest concurrent_batches signals_and_files)
  add_test(NAME cli.service.${script}
           COMMAND bash ${SUBDFIT_CLI_SCRIPTS}/service/${script}.sh $<TARGET_FILE:subdfit> ${SUBDFIT_CLI_OUT}/service_${script}
                   ${SUBDFIT_CLI_CAGE} ${SUBDFIT_CLI_REFERENCE})
  set_tests_properties(cli.service.${script} PROPERTIES LABELS cli TIMEOUT 300)
endforeach()

# Hostile inputs (tests/cli/hostile_inputs.sh): .subd files that state far more than they hold,
# `decode --out` at a FIFO, a folder, a symlink or the input, impossible sizes and counts.
add_test(NAME cli.hostile_inputs
         COMMAND bash ${SUBDFIT_CLI_SCRIPTS}/hostile_inputs.sh $<TARGET_FILE:subdfit> ${SUBDFIT_CLI_OUT}/hostile_inputs
                 ${PROJECT_SOURCE_DIR}/tests/data/hostile-subd ${SUBDFIT_CLI_REFERENCE} $<TARGET_FILE:subdfit-bench>)
set_tests_properties(cli.hostile_inputs PROPERTIES LABELS cli TIMEOUT 300)

# cmake -DSOURCE=<add-on folder> -DSTAGE=<scratch folder> -DZIP=<zip> -DVERSION=<x.y.z> -P this:
# the Blender add-on as an installable zip (one top folder, seqmassage_blender/), its bl_info
# "version" set to VERSION, so the zip, the module and the package carry the same version.
file(REMOVE_RECURSE ${STAGE})
file(MAKE_DIRECTORY ${STAGE}/seqmassage_blender)
file(GLOB sources ${SOURCE}/*.py)
file(COPY ${sources} DESTINATION ${STAGE}/seqmassage_blender)
string(REPLACE "." ", " version_tuple "${VERSION}")
file(READ ${STAGE}/seqmassage_blender/__init__.py init)
string(REGEX REPLACE "\"version\": \\([0-9, ]+\\)" "\"version\": (${version_tuple})" init "${init}")
if(NOT init MATCHES "\"version\": \\(${version_tuple}\\)")
  message(FATAL_ERROR "addon_zip: no \"version\": (...) in bl_info of ${SOURCE}/__init__.py")
endif()
file(WRITE ${STAGE}/seqmassage_blender/__init__.py "${init}")
file(REMOVE ${ZIP})
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${ZIP} --format=zip seqmassage_blender
                WORKING_DIRECTORY ${STAGE} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "addon_zip: could not write ${ZIP}")
endif()

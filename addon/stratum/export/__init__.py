"""Scene export: the evaluated depsgraph -> numpy arrays -> a native scene (the Blender side).

Imported module by module (this file imports nothing, so the pure modules below import without
bpy, for their unit tests):

    sync.py             export_scene (a whole scene, once) and SceneSync (a scene kept in step
                        with the depsgraph's changes, for the viewport), which use:
    updates.py          the depsgraph's updates, sorted into what changed
    object_sync.py      live edits of objects and lights
    placements.py       what full() places, row by row of the depsgraph's object instances
    instances.py        depsgraph object instances: transforms, visibility, holdout
    motion.py           transforms at shutter open and close (motion blur)
    geometry.py         an object's evaluated geometry -> native meshes, per material slot
    meshes.py           a mesh -> triangle, normal, UV, tangent and attribute arrays
    vertex_normals.py   vertex normals that are the same on every export (Blender < 4.1)
    mikktspace.py       MikkTSpace tangents on the exported triangles (pure numpy)
    placement.py        which transforms can be rendered (finite, not degenerate; pure numpy)
    render_geometry.py  the viewport depsgraph made to show the render's geometry (scripts)
    unsupported.py      objects and features Stratum does not render, one warning per kind
    materials.py        materials -> native closures (through stratum.shaders), MaterialTable
    images.py           image textures -> native textures; color_management.py their colour
    lights.py           lamps -> native lights; light_nodes.py their emission node trees
    world.py            the world -> background colour, environment image or node program
    camera.py           the scene camera -> native camera
    common.py           errors, the export summary, matrices, node-tree helpers
"""

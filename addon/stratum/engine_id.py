"""The name Blender knows Stratum's render engine by: RenderEngine.bl_idname, the value of
scene.render.engine, and the entry the add-on adds to the COMPAT_ENGINES of the panels it
shows. Without bpy, so the CLI's scripts for Blender and the comparison tool name it too."""

ENGINE_ID = "STRATUM"

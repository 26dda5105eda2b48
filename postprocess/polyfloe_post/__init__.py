"""Code the plotting scripts in postprocess/ share. The scripts run from their own folder (Python puts it first on
the module path), so `from polyfloe_post.frames import frame_polygons` needs no setting of the path."""

"""Geometry core: the ball-centre helix and its frames, groove profiles and curvatures, four-point contact geometry."""

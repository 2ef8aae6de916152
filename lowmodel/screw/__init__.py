"""Ball-screw kinematics (wang2022) and Harris's bearing kinematics."""

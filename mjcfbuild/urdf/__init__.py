"""URDF: the data model, parsing, file resolution, transforms and forward kinematics."""

"""Building the MuJoCo model: bodies from links, inertia checks, assembly on MjSpec, scene."""

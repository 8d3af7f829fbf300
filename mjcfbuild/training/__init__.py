"""The training variant: a model for batched simulation (MuJoCo Warp, MJX) built beside the
full one, with primitive collision geometry, few contacts and bounded solver work."""

"""Proving a built model against its source with code independent of MuJoCo's URDF import."""

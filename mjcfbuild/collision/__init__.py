"""Collision geometry: which shapes collide (policies), convex decomposition, primitive fits."""

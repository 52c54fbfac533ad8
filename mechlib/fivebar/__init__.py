"""Planar 5R symmetrical parallel mechanism: kinematics, identification, posture selection."""

"""Planar 5R symmetrical parallel mechanism: kinematics and MIW, the singularity field and the
drawn chains, and its instance of the calibration core with its chapter's study (mechanism)."""

"""Mechanism-independent leg-wise (divide and conquer) kinematic calibration: legs and mechanisms
(:mod:`.mechanism`), identification and identifiability (:mod:`.identify`), observability indices
and pose selection (:mod:`.selection`), the Monte Carlo study (:mod:`.study`) and the cost of the
normal equations (:mod:`.cost`)."""

"""The parallelogram flexure (two parallel beams and a stage): the published 3-D FE benchmark of
Su & Survey (:mod:`.published`) and our elastica reference model (:mod:`.elastica`)."""

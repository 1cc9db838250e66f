"""The rolling models: bodies, cases, reduced systems, kinematics, the independent
reference field."""

"""Teaching scenes, the planner that runs each on the smallest model, and the scene checks."""

"""The independent albedo sweep (issue 24): truths by a third route, checked against the engine and the disk."""

"""ballbench validation: scenes, harness, reports and the ``ballbench`` CLI."""

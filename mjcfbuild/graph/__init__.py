"""The generic parts of the task graph, below the families that declare tasks and above the
steps they run: the build's configuration, task families and file tasks, up-to-date checks and
file hashes. The engine (above) runs the graph; it gives each build its session."""

"""Developer tools: the benchmark (``bench``), the hard-case suite (``hard``) and its report (``check``)."""

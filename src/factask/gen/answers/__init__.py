"""What a model's answer must look like: the JSON schema of a whole graph, of each
factorized step, and the library's graphs used as worked examples.

May import the task library, the graph model and the layers below; never the reading of
proposals (:mod:`factask.gen.reading`) or the LLM pipeline.
"""

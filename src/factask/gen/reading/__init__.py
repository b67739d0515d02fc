"""Reading a proposal's words: the objects and colours it mentions, their bases, which
relations cover them, what fits on the table, and the grounded answer schema built
from all that (the grammar a model's answer is held to).

May import the answer schemas (:mod:`factask.gen.answers.schemas`,
:mod:`factask.gen.answers.step_schemas`), the example graphs (:mod:`factask.gen.answers.examples`),
the layout solver and the layers below; never the LLM pipeline (clients, steps,
strategies, conversations).
"""

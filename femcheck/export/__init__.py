"""Export of femcheck's FE scenes as Abaqus / CalculiX input decks, and a reader of CalculiX results.

One module per job: :mod:`.model` the format-neutral deck (nodes, elements, sets, contact, steps),
:mod:`.elements` element types, quadratic promotion and face numbering, :mod:`.indenter` the meshed rigid
indenter, :mod:`.scenes` a scene kind -> its deck (point, line, roller contact; :mod:`.layered`,
:mod:`.srb`, :mod:`.friction`, :mod:`.bearing` the other kinds, :mod:`.assemble` their common indentation deck),
:mod:`.deck` the keyword writer, :mod:`.frd` the reader of
``.frd`` / ``.dat`` results, :mod:`.inp` a reader and format check of the decks, :mod:`.pressure` the contact
pressure and femcheck's estimators on those results, :mod:`.write` the entry point (:func:`.write.export`),
:mod:`.run` running ``ccx``, :mod:`.calculix_model` the ``calculix`` model of the comparisons.
"""

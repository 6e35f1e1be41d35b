"""The cycle machinery below the studies: the EHL pass along the cam cycle
(:mod:`.driver`, its data :mod:`.data`, the thermal method :mod:`.thermal`, the table of
methods :mod:`.methods`), the implicit coupling with the dynamics (:mod:`.coupling`,
:mod:`.film_laws`) and the task graph runner (:mod:`.tasks`)."""

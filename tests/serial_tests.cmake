# Tests that need a core of their own (a live loop spinning at 1 kHz beside a client, or
# bursts of slow frames that must step the m' governor down on time): CTest runs them
# alone. Read by CTest after the discovered doctest cases.
set_tests_properties("live bridge: a 1 kHz client for 10 s, a silent one, malformed datagrams and a second client"
                     "live session: one loop for 30 s, its m', passivity and slew carried over recordings and a reset"
                     PROPERTIES RUN_SERIAL TRUE)

# target_sources(adaptex_param PRIVATE ...) for cut / pack / unwrap

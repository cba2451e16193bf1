# adaptex_add_test(...) calls go here

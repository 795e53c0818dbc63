# Doxygen input filter: the headers document their declarations with plain
# // comments; read a comment line as a doc comment (///) and a comment after a
# member on the same line as a trailing doc comment (///<). Lines already
# /// or //! are left alone.
s#^([[:space:]]*)//([^/!]|$)#\1///\2#
s#([;,{])([[:space:]]*)//([^/!])#\1\2///<\3#

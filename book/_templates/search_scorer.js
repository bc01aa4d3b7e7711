/* The book's search ranking (Sphinx's html_search_scorer, set by book/_ext/offline_book.py):
   Sphinx's own scores, except that the API reference's entries come after every chapter that
   has the words searched for. A student searching "RMS" wants chapter 3 first; the function
   rsgeo.evaluate.rms is still found, below it. */
var Scorer = {
  score: (result) => {
    const [docname, title, anchor, descr, score] = result;
    const isApiEntry = /(^|\/)api$/.test(docname) && anchor !== "";
    return isApiEntry ? score - 20 : score;
  },
  // Sphinx 7.4's defaults
  objNameMatch: 11,
  objPartialMatch: 6,
  objPrio: {
    0: 15,
    1: 5,
    2: -5,
  },
  objPrioDefault: 0,
  title: 15,
  partialTitle: 7,
  term: 5,
  partialTerm: 2,
};
